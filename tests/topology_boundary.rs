//! Boundary points: does the intersection curve enter the domain there, leave it or touch it?
//!
//! Every expected answer comes from a closed form of the test geometry (circles and lines in the
//! parameter plane), not from the code: the seed paper's (Oh, Hur & Kim) critical example with
//! its perturbations, an oblique plane through a paraboloid, circles tangent to a domain edge,
//! and the marched branches of the repository scenes (first point enters, last point leaves).

mod common;

use common::scenes::scene;
use common::surfaces::height_field;
use ssitrace::error::Error;
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::{Domain, ParametricSurface, PowerSurface, RationalBezierPatch};
use ssitrace::march::branch::{BranchStatus, EndReason};
use ssitrace::march::MarchOptions;
use ssitrace::pair::boundary_direction::{
    boundary_sides, classify_boundary_point, classify_boundary_point_unproven, classify_on_faces,
    Bound, BoundaryClassification, BoundaryDirection, BoundaryOptions, BoundarySide, DecidedBy,
};
use ssitrace::pair::contact_quadratic::ContactCase;
use ssitrace::search::start_points::SearchOptions;
use ssitrace::topology::intersect::intersect;

fn classify(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: [f64; 4],
    side: BoundarySide,
) -> BoundaryClassification {
    classify_boundary_point(p, q, y, side, &BoundaryOptions::default()).expect("classifies")
}

// ---------------------------------------------------------------------------------------------
// Seed 001: f = (u, v, 0), g = (0.7s + 0.15, 0.7t + 0.15, (t − 0.5)³ + ε) on [0,1]².
// P = f with parameters (σ, t) = (u, v); Q = g with parameters (u, v) = (s, t): the paper's s is
// coordinate 2, its t coordinate 3. For every ε the intersection is the line
// t = 0.5 − ∛ε, s ∈ [0, 1], so dt/ds = 0 (and dσ/ds = 0.7, dτ/ds = 0 on f); it enters g's domain
// at s = 0 and leaves it at s = 1 (travelling along N^P × N^Q = +x, as s increases).

fn paper_f() -> RationalBezierPatch {
    height_field(Domain::UNIT, vec![(0, 0, 0.0), (1, 1, 0.0)])
}

fn paper_g(eps: f64) -> RationalBezierPatch {
    PowerSurface {
        domain: Domain::UNIT,
        x: vec![(1, 0, 0.7), (0, 0, 0.15)],
        y: vec![(0, 1, 0.7), (0, 0, 0.15)],
        // (t − 0.5)³ + ε = t³ − 1.5 t² + 0.75 t − 0.125 + ε
        z: vec![
            (0, 3, 1.0),
            (0, 2, -1.5),
            (0, 1, 0.75),
            (0, 0, -0.125 + eps),
        ],
        w: None,
    }
    .to_bezier()
    .expect("valid patch")
}

/// The paper's boundary point at s = `s` for perturbation ε: t = 0.5 − ∛ε.
fn paper_point(eps: f64, s: f64) -> [f64; 4] {
    let t = 0.5 - eps.cbrt();
    [0.7 * s + 0.15, 0.7 * t + 0.15, s, t]
}

fn name(d: BoundaryDirection) -> &'static str {
    match d {
        BoundaryDirection::Enters => "enters (start)",
        BoundaryDirection::Leaves => "leaves (end)",
        BoundaryDirection::Touches { inside: true } => "touches, inside",
        BoundaryDirection::Touches { inside: false } => "touches, outside",
        BoundaryDirection::Isolated => "isolated",
        BoundaryDirection::Undecided => "undecided",
    }
}

#[test]
fn seed_example_perturbed_problems_are_regular_with_dt_ds_zero() {
    let f = paper_f();
    println!("\nSeed 001 example, perturbed problems (regular, Grandine's test on eq. 4):");
    println!(
        "{:>9} | {:>8} | {:>10} | {:>10} | {:>11} | {:>15} | {:>15} | proven",
        "ε", "t", "dt/ds", "du/ds", "det (4)", "s = 0", "s = 1"
    );
    for eps in [0.1, 1e-2, 1e-3, 1e-6, -1e-6, -1e-3, -1e-2, -0.1] {
        let g = paper_g(eps);
        let start = classify(
            &f,
            &g,
            paper_point(eps, 0.0),
            BoundarySide::new(2, Bound::Min),
        );
        let end = classify(
            &f,
            &g,
            paper_point(eps, 1.0),
            BoundarySide::new(2, Bound::Max),
        );
        for (c, expect) in [
            (&start, BoundaryDirection::Enters),
            (&end, BoundaryDirection::Leaves),
        ] {
            assert!(!c.critical, "ε = {eps}: regular");
            assert_eq!(c.direction, expect, "ε = {eps}");
            assert!(c.proven, "ε = {eps}: the sign should be proven");
            let d = c
                .face_derivatives(BoundarySide::new(2, Bound::Min))
                .expect("transversal to the face");
            // (dσ/ds, dτ/ds, 1, dt/ds) = (0.7, 0, 1, 0) in closed form.
            assert!((d[0] - 0.7).abs() < 1e-12, "dσ/ds = {}", d[0]);
            assert!(d[1].abs() < 1e-12 && d[3].abs() < 1e-12, "{d:?}");
            // Travelling along +x (s increasing) the start enters.
            assert_eq!(c.along([1.0, 0.0, 0.0]), expect);
        }
        let d = start
            .face_derivatives(BoundarySide::new(2, Bound::Min))
            .unwrap();
        // The paper's "vanishing condition dt/ds·ε^(2/3) = 0": the determinant of eq. (4),
        // det(f_u, f_v, −g_t), is −3(t − 0.5)² = −3 ε^(2/3) (tends to 0: critical at ε = 0).
        let y = start.point;
        let (df, dg) = (f.derivs(y[0], y[1]), g.derivs(y[2], y[3]));
        let det = df.su.dot(&df.sv.cross(&(-dg.sv)));
        let closed = -3.0 * eps.cbrt().powi(2);
        assert!(
            (det - closed).abs() < 1e-12,
            "ε {eps}: det {det} vs {closed}"
        );
        println!(
            "{:>9.0e} | {:>8.5} | {:>10.2e} | {:>10.6} | {:>11.4e} | {:>15} | {:>15} | {}",
            eps,
            start.point[3],
            d[3],
            d[0],
            det,
            name(start.direction),
            name(end.direction),
            start.proven && end.proven
        );
    }
}

#[test]
fn seed_example_critical_case_by_perturbation_limit() {
    let f = paper_f();
    let g = paper_g(0.0);
    println!("\nSeed 001 example, ε = 0 (contact of order two along t = 0.5): critical points");
    for (s, side, expect) in [
        (
            0.0,
            BoundarySide::new(2, Bound::Min),
            BoundaryDirection::Enters,
        ),
        (
            1.0,
            BoundarySide::new(2, Bound::Max),
            BoundaryDirection::Leaves,
        ),
    ] {
        let c = classify(&f, &g, paper_point(0.0, s), side);
        assert!(c.critical, "the surfaces are tangent along t = 0.5");
        assert!(!c.proven, "a perturbation limit is never claimed as proven");
        assert_eq!(c.decided_by, DecidedBy::PerturbationLimit);
        // Contact of order two: every second-order term of the contact vanishes.
        assert_eq!(c.contact, Some(ContactCase::HigherOrder));
        assert_eq!(c.direction, expect, "s = {s}");
        // The orientation agreed by all perturbed problems is +x (N^P × N^Q for either sign of ε).
        assert!(c.orientation[0] > 0.999, "{:?}", c.orientation);
        let d = c.face_derivatives(side).expect("crosses the face");
        assert!(d[3].abs() < 1e-9, "dt/ds(0) = {}", d[3]);
        assert!((d[0] - 0.7).abs() < 1e-9);
        // Every perturbed problem: the point t = 0.5 − ∛ε (ε along n = +z) and dt/ds(ε) = 0;
        // both signs of ε occur.
        assert!(c.perturbed.iter().any(|p| p.epsilon > 0.0));
        assert!(c.perturbed.iter().any(|p| p.epsilon < 0.0));
        println!(
            "  s = {s}: {:>9} | {:>10} | {:>10}",
            "ε", "t(ε)", "dt/ds(ε)"
        );
        for pd in &c.perturbed {
            let t = 0.5 - pd.epsilon.cbrt();
            assert!(
                (pd.point[3] - t).abs() < 1e-9,
                "ε {}: t {}",
                pd.epsilon,
                pd.point[3]
            );
            assert_eq!(pd.point[2], s);
            let dtds = pd.tangent[3] / pd.tangent[2];
            assert!(dtds.abs() < 1e-9);
            println!(
                "  {:>16.1e} | {:>10.6} | {:>10.1e}",
                pd.epsilon, pd.point[3], dtds
            );
        }
        println!(
            "  limit: dt/ds(0) = {:.1e}, {} (decided by {:?}, proven {})",
            d[3],
            name(c.direction),
            c.decided_by,
            c.proven
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Regular cases: P the paraboloid z = σ² + t² on [0,1]², Q the plane z = 0.3 + 0.2u − 0.1v (both
// graphs over the same xy, so (u, v) = (σ, t) on the curve). The curve is the circle
// d(σ,t) = σ² + t² − 0.3 − 0.2σ + 0.1t = 0, centre (0.1, −0.05), radius² 0.3125, and
// N^P × N^Q runs along (−∂d/∂t, ∂d/∂σ): counter-clockwise.

fn oblique_pair(q_domain: Domain) -> (RationalBezierPatch, RationalBezierPatch) {
    (
        height_field(Domain::UNIT, vec![(2, 0, 1.0), (0, 2, 1.0)]),
        height_field(q_domain, vec![(0, 0, 0.3), (1, 0, 0.2), (0, 1, -0.1)]),
    )
}

/// The unit (σ', t') of the closed form at (σ, t).
fn circle_direction(s: f64, t: f64) -> [f64; 2] {
    let (a, b) = (-(2.0 * t + 0.1), 2.0 * s - 0.2);
    let n = a.hypot(b);
    [a / n, b / n]
}

fn assert_direction(c: &BoundaryClassification, s: f64, t: f64) {
    let e = circle_direction(s, t);
    let n = c.tangent[0].hypot(c.tangent[1]);
    assert!(
        (c.tangent[0] / n - e[0]).abs() < 1e-9 && (c.tangent[1] / n - e[1]).abs() < 1e-9,
        "tangent {:?} vs closed form {e:?}",
        c.tangent
    );
}

#[test]
fn oblique_plane_enters_at_one_end_and_leaves_at_the_other() {
    let (p, q) = oblique_pair(Domain::new(-1.0, 2.0, -1.0, 2.0));
    // t = 0: (σ − 0.1)² = 0.31; σ = 0: (t + 0.05)² = 0.3025, t = 0.5.
    let sa = 0.1 + 0.31f64.sqrt();
    let a = classify(&p, &q, [sa, 0.0, sa, 0.0], BoundarySide::new(1, Bound::Min));
    let b = classify(
        &p,
        &q,
        [0.0, 0.5, 0.0, 0.5],
        BoundarySide::new(0, Bound::Min),
    );
    assert_eq!(a.direction, BoundaryDirection::Enters);
    assert_eq!(b.direction, BoundaryDirection::Leaves);
    assert!(a.proven && b.proven && !a.critical && !b.critical);
    assert_eq!(a.decided_by, DecidedBy::FirstOrder);
    assert_direction(&a, sa, 0.0);
    assert_direction(&b, 0.0, 0.5);
    // The opposite traveller sees the opposite answers.
    let back = a.orientation.map(|x| -x);
    assert_eq!(a.along(back), BoundaryDirection::Leaves);
    assert_eq!(a.along(a.orientation), BoundaryDirection::Enters);
    // The same answers without the interval proof (f64 surfaces only), not claimed proven.
    let u = classify_boundary_point_unproven(
        &p,
        &q,
        [sa, 0.0, sa, 0.0],
        BoundarySide::new(1, Bound::Min),
        &BoundaryOptions::default(),
    )
    .unwrap();
    assert_eq!(u.direction, BoundaryDirection::Enters);
    assert!(!u.proven);
}

#[test]
fn oblique_plane_leaves_the_smaller_domain_of_q() {
    // Q restricted to u ≥ 0.5: the circle (counter-clockwise) leaves it at σ = u = 0.5,
    // t = −0.05 + √0.1525, where u' = −(2t + 0.1) < 0.
    let (p, q) = oblique_pair(Domain::new(0.5, 2.0, -1.0, 2.0));
    let t = -0.05 + 0.1525f64.sqrt();
    let y = [0.5, t, 0.5, t];
    let sides = boundary_sides(&p, &q, &y, 1e-12);
    assert_eq!(sides, vec![BoundarySide::new(2, Bound::Min)]);
    let c = classify(&p, &q, y, sides[0]);
    assert_eq!(c.direction, BoundaryDirection::Leaves);
    assert!(c.proven);
    assert_direction(&c, 0.5, t);
    assert!(
        (c.tangent[2] - c.tangent[0]).abs() < 1e-12,
        "u' = σ' on the curve"
    );
}

#[test]
fn curve_through_a_corner_enters_through_both_faces() {
    // P: z = σ² + t² on [0,1]², Q: z = −0.2u + 0.3v. The circle σ² + t² + 0.2σ − 0.3t = 0 passes
    // through the corner (0, 0) with direction (−∂d/∂t, ∂d/∂σ) = (0.3, 0.2): into the domain
    // across both faces σ = 0 and t = 0.
    let p = height_field(Domain::UNIT, vec![(2, 0, 1.0), (0, 2, 1.0)]);
    let q = height_field(
        Domain::new(-1.0, 2.0, -1.0, 2.0),
        vec![(1, 0, -0.2), (0, 1, 0.3)],
    );
    let faces = classify_on_faces(&p, &q, [0.0; 4], &BoundaryOptions::default()).unwrap();
    let sides: Vec<BoundarySide> = faces.iter().map(|f| f.0).collect();
    assert_eq!(
        sides,
        vec![
            BoundarySide::new(0, Bound::Min),
            BoundarySide::new(1, Bound::Min)
        ]
    );
    for (side, c) in &faces {
        assert_eq!(c.direction, BoundaryDirection::Enters, "{side:?}");
        assert!(c.proven);
        let ratio = c.tangent[1] / c.tangent[0];
        assert!((ratio - 0.2 / 0.3).abs() < 1e-12, "{ratio}");
    }
    // A point inside both domains lies on no face.
    let inside = [0.25, 0.0, 0.25, 0.0];
    assert!(boundary_sides(&p, &q, &[0.3, 0.4, 0.3, 0.4], 1e-9).is_empty());
    assert_eq!(boundary_sides(&p, &q, &inside, 1e-9).len(), 1);
}

// ---------------------------------------------------------------------------------------------
// Touching: P the paraboloid z = σ² + t², Q the plane z = 0.25: the circle σ² + t² = 0.25.

fn touching_pair(p_domain: Domain, q_domain: Domain) -> (RationalBezierPatch, RationalBezierPatch) {
    (
        height_field(p_domain, vec![(2, 0, 1.0), (0, 2, 1.0)]),
        height_field(q_domain, vec![(0, 0, 0.25)]),
    )
}

#[test]
fn circle_tangent_to_an_edge_touches_it() {
    let big = Domain::new(-2.0, 2.0, -2.0, 2.0);
    let cases = [
        // (P's domain, Q's domain, point, face, inside)
        (
            Domain::new(-1.0, 1.0, -0.5, 1.0),
            big,
            [0.0, -0.5, 0.0, -0.5],
            BoundarySide::new(1, Bound::Min),
            true,
        ),
        (
            Domain::new(-1.0, 1.0, 0.5, 1.0),
            big,
            [0.0, 0.5, 0.0, 0.5],
            BoundarySide::new(1, Bound::Min),
            false,
        ),
        (
            Domain::new(-1.0, 1.0, -1.0, 0.5),
            big,
            [0.0, 0.5, 0.0, 0.5],
            BoundarySide::new(1, Bound::Max),
            true,
        ),
        (
            Domain::new(-0.5, 1.0, -1.0, 1.0),
            big,
            [-0.5, 0.0, -0.5, 0.0],
            BoundarySide::new(0, Bound::Min),
            true,
        ),
        (
            big,
            Domain::new(-1.0, 1.0, -0.5, 1.0),
            [0.0, -0.5, 0.0, -0.5],
            BoundarySide::new(3, Bound::Min),
            true,
        ),
        (
            big,
            Domain::new(-1.0, 0.5, -1.0, 1.0),
            [0.5, 0.0, 0.5, 0.0],
            BoundarySide::new(2, Bound::Max),
            true,
        ),
        (
            big,
            Domain::new(0.5, 1.0, -1.0, 1.0),
            [0.5, 0.0, 0.5, 0.0],
            BoundarySide::new(2, Bound::Min),
            false,
        ),
    ];
    for (dp, dq, y, side, inside) in cases {
        let (p, q) = touching_pair(dp, dq);
        let c = classify(&p, &q, y, side);
        assert_eq!(
            c.direction,
            BoundaryDirection::Touches { inside },
            "{side:?} at {y:?}"
        );
        assert_eq!(c.decided_by, DecidedBy::SecondOrder);
        assert!(!c.proven && !c.critical);
        // The tangent runs along the face.
        assert!(c.tangent[side.coordinate].abs() < 1e-12);
    }
}

// ---------------------------------------------------------------------------------------------
// Other critical cases.

#[test]
fn isolated_contact_on_an_edge_is_isolated() {
    // The paraboloid z = σ² + t² on [−1,1]×[0,1] touches the plane z = 0 at the origin only.
    let p = height_field(
        Domain::new(-1.0, 1.0, 0.0, 1.0),
        vec![(2, 0, 1.0), (0, 2, 1.0)],
    );
    let q = height_field(
        Domain::new(-2.0, 2.0, -2.0, 2.0),
        vec![(0, 0, 0.0), (1, 1, 0.0)],
    );
    let c = classify(&p, &q, [0.0; 4], BoundarySide::new(1, Bound::Min));
    assert!(c.critical);
    assert_eq!(c.direction, BoundaryDirection::Isolated);
    assert_eq!(c.contact, Some(ContactCase::IsolatedPoint));
    assert_eq!(c.decided_by, DecidedBy::ContactQuadratic);
}

#[test]
fn tangent_plane_at_an_edge_of_the_rational_sphere_patch_is_isolated() {
    // The sphere scene's patch (radius 1.5625 about the origin) has P(0.5, 0) = (1.25, 0, −0.9375)
    // on its edge t = 0; Q is the tangent plane there, spanned by (0, 1, 0) and (0.6, 0, 0.8)
    // (normal (0.8, 0, −0.6)), with Q(0, 0) the point: the sphere touches it only there.
    let [p, _] = scene("sphere_patch_plane.json").surfaces;
    let corners: Vec<[f64; 3]> = [[-1.0, -1.0], [-1.0, 1.0], [1.0, -1.0], [1.0, 1.0]]
        .iter()
        .map(|&[u, v]| [1.25 + 0.6 * v, u, -0.9375 + 0.8 * v])
        .collect();
    let q = RationalBezierPatch::from_f64_points(
        [1, 1],
        &corners,
        None,
        Domain::new(-1.0, 1.0, -1.0, 1.0),
    )
    .unwrap();
    let y = [0.5, 0.0, 0.0, 0.0];
    let at = p.point(0.5, 0.0);
    assert!((at - nalgebra::Vector3::new(1.25, 0.0, -0.9375)).norm() < 1e-12);
    let c = classify(&p, &q, y, BoundarySide::new(1, Bound::Min));
    assert!(c.critical);
    assert_eq!(c.contact, Some(ContactCase::IsolatedPoint));
    assert_eq!(c.direction, BoundaryDirection::Isolated);
}

#[test]
fn branch_point_on_an_edge_is_reported_undecided() {
    // z = σ² − t² on [−1,1]×[0,1] meets the plane z = 0 in the lines σ = ±t, which cross at the
    // origin on the edge t = 0: two branches start there, no single direction exists.
    let p = height_field(
        Domain::new(-1.0, 1.0, 0.0, 1.0),
        vec![(2, 0, 1.0), (0, 2, -1.0)],
    );
    let q = height_field(
        Domain::new(-2.0, 2.0, -2.0, 2.0),
        vec![(0, 0, 0.0), (1, 1, 0.0)],
    );
    let c = classify(&p, &q, [0.0; 4], BoundarySide::new(1, Bound::Min));
    assert!(c.critical && !c.proven);
    assert_eq!(c.contact, Some(ContactCase::BranchPoint));
    assert_eq!(c.direction, BoundaryDirection::Undecided);
}

#[test]
fn tangential_line_of_order_one_is_a_branch_end_oriented_inward() {
    // z = (t − 0.5)² on [0,1]² touches the plane z = 0 along t = 0.5: a branch from σ = 0 to 1.
    // The perturbed curves t = 0.5 ± √ε come in oppositely oriented pairs, so the answer is
    // oriented into the domain: Enters at both ends, with orientation +x at σ = 0, −x at σ = 1.
    let p = height_field(Domain::UNIT, vec![(0, 2, 1.0), (0, 1, -1.0), (0, 0, 0.25)]);
    let q = height_field(
        Domain::new(-1.0, 2.0, -1.0, 2.0),
        vec![(0, 0, 0.0), (1, 1, 0.0)],
    );
    for (s, side, ox) in [
        (0.0, BoundarySide::new(0, Bound::Min), 1.0),
        (1.0, BoundarySide::new(0, Bound::Max), -1.0),
    ] {
        let c = classify(&p, &q, [s, 0.5, s, 0.5], side);
        assert!(c.critical);
        assert_eq!(c.direction, BoundaryDirection::Enters);
        assert_eq!(c.decided_by, DecidedBy::PerturbationLimit);
        assert_eq!(c.contact, Some(ContactCase::TangentialCurve));
        assert!(c.orientation[0] * ox > 0.999, "{:?}", c.orientation);
        let d = c.face_derivatives(side).unwrap();
        assert!(d[1].abs() < 1e-6 && (d[2] - 1.0).abs() < 1e-6, "{d:?}");
    }
}

#[test]
fn oblique_tangential_line_of_order_one_crosses_the_t_faces() {
    // z = (σ − 0.5 − 0.2t)² touches z = 0 along σ = 0.5 + 0.2t, from (0.5, 0) to (0.7, 1):
    // dσ/dt = 0.2; oriented into the domain at both ends (as the trough above).
    let p = height_field(
        Domain::UNIT,
        vec![
            (2, 0, 1.0),
            (1, 1, -0.4),
            (0, 2, 0.04),
            (1, 0, -1.0),
            (0, 1, 0.2),
            (0, 0, 0.25),
        ],
    );
    let q = height_field(
        Domain::new(-1.0, 2.0, -1.0, 2.0),
        vec![(0, 0, 0.0), (1, 1, 0.0)],
    );
    for (y, side, oy) in [
        ([0.5, 0.0, 0.5, 0.0], BoundarySide::new(1, Bound::Min), 1.0),
        ([0.7, 1.0, 0.7, 1.0], BoundarySide::new(1, Bound::Max), -1.0),
    ] {
        let c = classify(&p, &q, y, side);
        assert!(c.critical);
        assert_eq!(c.contact, Some(ContactCase::TangentialCurve));
        assert_eq!(c.direction, BoundaryDirection::Enters, "{side:?}");
        assert!(c.orientation[1] * oy > 0.9, "{:?}", c.orientation);
        let d = c.face_derivatives(side).unwrap();
        assert!(
            (d[0] - 0.2).abs() < 1e-6 && (d[2] - 0.2).abs() < 1e-6,
            "{d:?}"
        );
    }
}

#[test]
fn critical_curved_tangential_curve_by_perturbation_limit() {
    // P: z = (1 + σ)(t − 0.5 − 0.3σ²)³ on [0,1]², Q: the plane z = 0. They touch (contact of
    // order two) along the parabola t = 0.5 + 0.3σ², whose slope dt/dσ = 0.6σ is 0 at σ = 0 and
    // 0.6 at σ = 1. Q moved by ε along n = N^P = +z meets P where h = ε: the perturbed curves
    // t = 0.5 + 0.3σ² + ∛(ε/(1 + σ)) have slope 0.6σ − ∛ε (1 + σ)^(−4/3)/3, so the limit is
    // approached like ∛ε. For graphs,
    // N^P × N^Q ∝ (−h_t, h_σ) = −3(1 + σ)w²(1, 0.6σ) + O(w³) with w = t − 0.5 − 0.3σ²: σ
    // decreases along it for either sign of ε, so the curve leaves at σ = 0 and enters at σ = 1.
    let terms = vec![
        (7, 0, -0.027),
        (6, 0, -0.027),
        (5, 1, 0.27),
        (5, 0, -0.135),
        (4, 1, 0.27),
        (4, 0, -0.135),
        (3, 2, -0.9),
        (3, 1, 0.9),
        (3, 0, -0.225),
        (2, 2, -0.9),
        (2, 1, 0.9),
        (2, 0, -0.225),
        (1, 3, 1.0),
        (1, 2, -1.5),
        (1, 1, 0.75),
        (1, 0, -0.125),
        (0, 3, 1.0),
        (0, 2, -1.5),
        (0, 1, 0.75),
        (0, 0, -0.125),
    ];
    let p = height_field(Domain::UNIT, terms);
    let q = height_field(
        Domain::new(-1.0, 2.0, -1.0, 2.0),
        vec![(0, 0, 0.0), (1, 1, 0.0)],
    );
    println!("\nCurved tangential curve of contact order two: dt/dσ(ε) → dt/dσ(0)");
    for (s, side, expect, slope) in [
        (
            0.0,
            BoundarySide::new(0, Bound::Min),
            BoundaryDirection::Leaves,
            0.0,
        ),
        (
            1.0,
            BoundarySide::new(0, Bound::Max),
            BoundaryDirection::Enters,
            0.6,
        ),
    ] {
        let t = 0.5 + 0.3 * s * s;
        let c = classify(&p, &q, [s, t, s, t], side);
        assert!(c.critical && !c.proven);
        assert_eq!(c.contact, Some(ContactCase::HigherOrder));
        assert_eq!(c.decided_by, DecidedBy::PerturbationLimit);
        assert_eq!(c.direction, expect, "σ = {s}");
        let d = c.face_derivatives(side).unwrap();
        println!(
            "  σ = {s}: {:>9} | {:>12} | {:>12}",
            "ε", "dt/dσ(ε)", "closed form"
        );
        for pd in &c.perturbed {
            let slope_eps = pd.tangent[1] / pd.tangent[0];
            let closed = 0.6 * s - pd.epsilon.cbrt() * (1.0 + s).powf(-4.0 / 3.0) / 3.0;
            assert!(
                (slope_eps - closed).abs() < 1e-6,
                "ε {}: {slope_eps} vs {closed}",
                pd.epsilon
            );
            println!(
                "  {:>16.1e} | {:>12.8} | {:>12.8}",
                pd.epsilon, slope_eps, closed
            );
        }
        println!(
            "  limit (mean over ±ε at the smallest level) dt/dσ(0) = {:.9} (exact {slope}, error {:.1e}), {}",
            d[1],
            d[1] - slope,
            name(c.direction)
        );
        assert!(
            (d[1] - slope).abs() < 1e-3,
            "dt/dσ(0) = {} vs {slope}",
            d[1]
        );
    }
}

#[test]
fn seed_example_rotated_in_space_keeps_its_answers() {
    // The same pair after a rigid rotation of model space (control points rotated; rational
    // Bézier patches are affinely invariant): the answers must not depend on the axes.
    let (c1, s1) = (0.6, 0.8);
    let (c2, s2) = (5.0 / 13.0, 12.0 / 13.0);
    let rotate = |x: [f64; 3]| {
        let a = [x[0], c1 * x[1] - s1 * x[2], s1 * x[1] + c1 * x[2]];
        [c2 * a[0] - s2 * a[1], s2 * a[0] + c2 * a[1], a[2]]
    };
    let rotated = |patch: &RationalBezierPatch| {
        let pts: Vec<[f64; 3]> = patch
            .cartesian()
            .iter()
            .map(|c| rotate([c[0].mid(), c[1].mid(), c[2].mid()]))
            .collect();
        RationalBezierPatch::from_f64_points(patch.degree(), &pts, None, Domain::UNIT).unwrap()
    };
    let (f, g) = (rotated(&paper_f()), rotated(&paper_g(0.0)));
    let along_s = rotate([1.0, 0.0, 0.0]);
    for (s, side, expect) in [
        (
            0.0,
            BoundarySide::new(2, Bound::Min),
            BoundaryDirection::Enters,
        ),
        (
            1.0,
            BoundarySide::new(2, Bound::Max),
            BoundaryDirection::Leaves,
        ),
    ] {
        let c = classify(&f, &g, paper_point(0.0, s), side);
        assert!(c.critical);
        assert_eq!(c.direction, expect);
        assert_eq!(c.along(along_s), expect);
        let d = c.face_derivatives(side).unwrap();
        assert!(d[3].abs() < 1e-6 && (d[0] - 0.7).abs() < 1e-6, "{d:?}");
    }
}

#[test]
fn critical_curve_along_the_face_is_undecided() {
    // g = (0.7s + 0.15, 0.7t + 0.15, t³) touches f = (u, v, 0) along its own edge t = 0.
    let f = paper_f();
    let g = PowerSurface {
        domain: Domain::UNIT,
        x: vec![(1, 0, 0.7), (0, 0, 0.15)],
        y: vec![(0, 1, 0.7), (0, 0, 0.15)],
        z: vec![(0, 3, 1.0)],
        w: None,
    }
    .to_bezier()
    .unwrap();
    let c = classify(
        &f,
        &g,
        [0.5, 0.15, 0.5, 0.0],
        BoundarySide::new(3, Bound::Min),
    );
    assert!(c.critical);
    assert_eq!(c.direction, BoundaryDirection::Undecided);
    assert!(!c.proven);
}

// ---------------------------------------------------------------------------------------------
// Consistency with the marcher on the repository scenes: every open branch starts with a point
// that enters and ends with one that leaves, for the direction it was traced in.

/// The pairs checked: the bicubic scene as it is, and the sphere scene's rational sphere patch
/// with its plane moved from x = 1.375 (a closed circle) to x = 1.2, where the circle (radius 1
/// on the sphere of radius 1.5625) crosses the patch's edges, so its arcs are open branches.
fn scene_pairs() -> Vec<(&'static str, RationalBezierPatch, RationalBezierPatch, f64)> {
    let bicubic = scene("bicubic_transversal.json");
    let sphere = scene("sphere_patch_plane.json");
    let [bp, bq] = bicubic.surfaces;
    let [sp, _] = sphere.surfaces;
    let c = [[-1.0, -1.0], [-1.0, 1.0], [1.0, -1.0], [1.0, 1.0]];
    let plane: Vec<[f64; 3]> = c.iter().map(|&[y, z]| [1.2, y, z]).collect();
    let sq = RationalBezierPatch::from_f64_points([1, 1], &plane, None, Domain::UNIT).unwrap();
    vec![
        ("bicubic_transversal.json", bp, bq, bicubic.options.step),
        (
            "sphere_patch_plane.json, plane x = 1.2",
            sp,
            sq,
            sphere.options.step,
        ),
    ]
}

#[test]
fn marched_branches_enter_first_and_leave_last() {
    let opts = BoundaryOptions::default();
    for (file, p, q, step) in scene_pairs() {
        let (p, q) = (&p, &q);
        let march = MarchOptions {
            step,
            ..MarchOptions::default()
        };
        let out = intersect(p, q, &march, &SearchOptions::default());
        let (mut checked, mut proven) = (0, 0);
        for b in &out.intersection.branches {
            if b.status != BranchStatus::Open || b.points.len() < 2 {
                continue;
            }
            let n = b.points.len();
            let params = |k: usize| {
                let c = &b.points[k];
                [c.p[0], c.p[1], c.q[0], c.q[1]]
            };
            let travel = |a: usize, z: usize| {
                let (x, y) = (&b.points[a].xyz, &b.points[z].xyz);
                [y[0] - x[0], y[1] - x[1], y[2] - x[2]]
            };
            for (end, idx, dir, expect) in [
                (b.ends[0], 0, travel(0, 1), BoundaryDirection::Enters),
                (
                    b.ends[1],
                    n - 1,
                    travel(n - 2, n - 1),
                    BoundaryDirection::Leaves,
                ),
            ] {
                if !matches!(end, EndReason::Boundary { .. }) {
                    continue;
                }
                let y = params(idx);
                let faces = classify_on_faces(p, q, y, &opts).expect("classifies");
                assert!(
                    !faces.is_empty(),
                    "{file}: boundary end off every face: {y:?}"
                );
                for (side, c) in faces {
                    assert_eq!(
                        c.along(dir),
                        expect,
                        "{file}: branch {} at {y:?} {side:?}",
                        b.id
                    );
                    checked += 1;
                    proven += c.proven as usize;
                }
            }
        }
        println!(
            "{file}: {} branches, {checked} boundary ends agree with the marcher, {proven} proven",
            out.intersection.branches.len()
        );
        assert!(checked >= 2, "{file}: no open branch to check");
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input.

#[test]
fn bad_inputs_are_typed_errors() {
    let (p, q) = oblique_pair(Domain::new(-1.0, 2.0, -1.0, 2.0));
    let o = BoundaryOptions::default();
    let side = BoundarySide::new(0, Bound::Min);
    let on = [0.0, 0.5, 0.0, 0.5];
    let r = classify_boundary_point(&p, &q, [0.0, f64::NAN, 0.0, 0.5], side, &o);
    assert!(matches!(r, Err(Error::InvalidInput { .. })), "{r:?}");
    let r = classify_boundary_point(&p, &q, on, BoundarySide::new(7, Bound::Min), &o);
    assert!(matches!(r, Err(Error::InvalidInput { .. })), "{r:?}");
    // Not on the face σ = 1.
    let r = classify_boundary_point(&p, &q, on, BoundarySide::new(0, Bound::Max), &o);
    assert!(
        matches!(r, Err(Error::NotOnBoundary { coordinate: 0, .. })),
        "{r:?}"
    );
    // On the face σ = 0 but not on the curve.
    let r = classify_boundary_point(&p, &q, [0.0, 0.3, 0.0, 0.3], side, &o);
    assert!(matches!(r, Err(Error::NotOnIntersection { .. })), "{r:?}");
    // Bad options.
    let bad = BoundaryOptions {
        residual_admission: -1.0,
        ..o
    };
    let r = classify_boundary_point(&p, &q, on, side, &bad);
    assert!(matches!(r, Err(Error::InvalidInput { .. })), "{r:?}");
    let bad = BoundaryOptions {
        proof_radii: [1e-9, f64::INFINITY, 1e-6],
        ..o
    };
    assert!(classify_boundary_point(&p, &q, on, side, &bad).is_err());
    // Infinite coordinates on an f64-only surface pair.
    let plane: fn(Jet2, Jet2) -> [Jet2; 3] = |u, v| [u, v, Jet2::constant(0.0)];
    let a = AnalyticSurface::new(Domain::UNIT, plane);
    let r = classify_boundary_point_unproven(&a, &a, [f64::INFINITY, 0.0, 0.0, 0.0], side, &o);
    assert!(matches!(r, Err(Error::InvalidInput { .. })), "{r:?}");
}
