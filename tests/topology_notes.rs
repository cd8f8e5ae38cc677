//! Topology notes of a run: boundary ends checked by Grandine's test, singular nodes with their
//! arcs, written into the result JSON and read back; and a closed curve that touches the domain
//! boundary from inside stays one closed loop (its touching points are neither starts nor ends).

mod common;

use common::scenes::scene;
use common::surfaces::height_field;
use ssitrace::geometry::Domain;
use ssitrace::io::result_json::{result_from_json, result_to_json};
use ssitrace::io::scene::Method;
use ssitrace::march::branch::{BranchStatus, EndReason, EventKind};
use ssitrace::march::MarchOptions;
use ssitrace::pipeline::{run, RunOptions};
use ssitrace::search::start_points::SearchOptions;
use ssitrace::topology::intersect::intersect;

#[test]
fn circle_touching_all_four_edges_from_inside_is_one_closed_loop() {
    // z = σ² + t² on [-0.5, 0.5]² against z = 0.25: the circle of radius 0.5 touches each edge
    // of P's domain at one point and lies inside otherwise.
    let p = height_field(
        Domain::new(-0.5, 0.5, -0.5, 0.5),
        vec![(2, 0, 1.0), (0, 2, 1.0)],
    );
    let q = height_field(Domain::new(-2.0, 2.0, -2.0, 2.0), vec![(0, 0, 0.25)]);
    let march = MarchOptions {
        step: 0.05,
        ..MarchOptions::default()
    };
    let out = intersect(&p, &q, &march, &SearchOptions::default());
    let branches = &out.intersection.branches;
    for b in branches {
        println!(
            "branch {}: {:?} {:?} {} points",
            b.id,
            b.status,
            b.ends,
            b.points.len()
        );
    }
    assert_eq!(branches.len(), 1, "one curve, one branch");
    let b = &branches[0];
    assert_eq!(b.status, BranchStatus::Closed);
    assert_eq!(b.ends, [EndReason::ClosedLoop; 2]);
    for c in &b.points {
        let r = (c.p[0] * c.p[0] + c.p[1] * c.p[1]).sqrt();
        assert!((r - 0.5).abs() < 1e-8, "point off the circle: r = {r}");
    }
    // Once round: the marched length is the circumference (within a step).
    let len = b.length();
    let circumference = std::f64::consts::PI;
    assert!(
        (len - circumference).abs() < march.step,
        "marched {len}, circle {circumference}"
    );
}

#[test]
fn boundary_ends_and_nodes_are_written_and_read_back() {
    for (file, nodes) in [("bicubic_transversal.json", 0), ("viviani.json", 1)] {
        let s = scene(file);
        let opts = RunOptions {
            method: Method::March,
            ..RunOptions::from_scene(&s)
        };
        let report = run(&s, &opts).expect("runs");
        let meta = &report.meta;
        assert_eq!(meta.stats["inconsistent_boundary_ends"], 0, "{file}");
        // Every boundary end of every branch is checked, proven, and seen the right way round.
        for b in &report.result.marched().branches {
            let expected = b
                .ends
                .iter()
                .filter(|e| matches!(e, EndReason::Boundary { .. }))
                .count();
            let notes = meta.branch_notes.get(&b.id);
            let ends = notes
                .and_then(|n| n.get("boundary_ends"))
                .and_then(|v| v.as_array())
                .map_or(0, |a| a.len());
            assert!(
                ends >= expected,
                "{file}: branch {} has {ends} checks",
                b.id
            );
            if let Some(a) = notes.and_then(|n| n["boundary_ends"].as_array()) {
                for c in a {
                    assert_eq!(c["proven"], true, "{file}: {c}");
                    let want = if c["end"] == 0 { "enters" } else { "leaves" };
                    assert_eq!(c["seen"], want, "{file}: {c}");
                }
            }
        }
        let node_notes: Vec<_> = meta
            .event_notes
            .values()
            .filter_map(|n| n.get("node"))
            .collect();
        assert_eq!(node_notes.len(), nodes, "{file}");
        for n in &node_notes {
            assert_eq!(n["case"], "branch_point", "{file}: {n}");
            assert_eq!(n["arcs"], 4, "{file}: {n}");
        }
        let doc = result_to_json(&report.result.marched(), meta);
        let back = result_from_json(&doc).expect("reads back");
        assert_eq!(back.meta.branch_notes, meta.branch_notes, "{file}");
        assert_eq!(back.meta.event_notes, meta.event_notes, "{file}");
    }
}

#[test]
fn circle_touching_an_edge_from_outside_gives_no_branch() {
    // The same circle against P's domain [-0.5, 0.5] × [0.5, 1.5]: it touches the face t = 0.5
    // at (0, 0.5) from outside, so the domain holds one point of it and no branch.
    let p = height_field(
        Domain::new(-0.5, 0.5, 0.5, 1.5),
        vec![(2, 0, 1.0), (0, 2, 1.0)],
    );
    let q = height_field(Domain::new(-2.0, 2.0, -2.0, 2.0), vec![(0, 0, 0.25)]);
    let march = MarchOptions {
        step: 0.05,
        ..MarchOptions::default()
    };
    let out = intersect(&p, &q, &march, &SearchOptions::default());
    for b in &out.intersection.branches {
        println!(
            "branch {}: {:?} {:?} {} points",
            b.id,
            b.status,
            b.ends,
            b.points.len()
        );
    }
    assert!(
        out.intersection.branches.is_empty(),
        "a touching point from outside is no branch"
    );
    // It is reported as a boundary event at the touching point (0, 0.5).
    let touch = out.intersection.events.iter().any(|e| {
        e.kind == EventKind::BoundaryEnd && e.p[0].abs() < 1e-7 && (e.p[1] - 0.5).abs() < 1e-12
    });
    assert!(touch, "events: {:?}", out.intersection.events);
}

#[test]
fn arcs_into_nodes_approach_them_in_few_points() {
    // Both tangent points of two crossing cylinders are nodes; an arc approaches a node
    // geometrically (halving the distance), so it needs about log2(step / 1e-6) ≈ 16 points per
    // node end beyond its length / step, not hundreds of rounding-sized steps.
    let s = scene("cylinders_full.json");
    let [p, q] = &s.surfaces;
    let march = MarchOptions {
        step: s.options.step,
        ..MarchOptions::default()
    };
    let out = intersect(p, q, &march, &SearchOptions::default());
    assert_eq!(out.intersection.branches.len(), 7);
    for b in &out.intersection.branches {
        let len = b.length();
        let node_ends = b.ends.iter().filter(|e| **e == EndReason::Singular).count();
        let bound = 1.5 * len / march.step + 25.0 * node_ends as f64 + 5.0;
        println!(
            "arc {}: {} points, length {len:.4}, bound {bound:.0}",
            b.id,
            b.points.len()
        );
        assert!(
            (b.points.len() as f64) <= bound,
            "arc {}: {} points for length {len}",
            b.id,
            b.points.len()
        );
    }
}

#[test]
fn a_curve_of_tangency_is_one_certified_contact_and_no_branch() {
    // P − Q = (1 + 0.3x)(y − x/2)² on [−1, 1]²: the surfaces touch along y = x/2 and nowhere
    // cross. Its singular points are contacts (no arcs), so the run has no branch, and the
    // contact is certified once, every step a tangential curve.
    let s = scene("cubic_quadratic_tangential.json");
    let opts = RunOptions {
        method: Method::Both,
        ..RunOptions::from_scene(&s)
    };
    let report = run(&s, &opts).expect("runs");
    assert!(report.result.branches.is_empty());
    assert!(report.result.nodes.iter().all(|n| n.exits.is_empty()));
    assert_eq!(
        report.result.contacts.len(),
        1,
        "one contact, certified once"
    );
    let c = &report.result.contacts[0];
    assert!(!c.steps.is_empty());
    for st in &c.steps {
        assert_eq!(
            format!("{:?}", st.case),
            "TangentialCurve",
            "a step's case at s = {:?}",
            st.s
        );
    }
    assert!(c.tube_radius < 1e-9, "tube radius {}", c.tube_radius);
    // The closed-form contact line lies in the step boxes.
    for k in 0..=200 {
        let x = -0.99 + 1.98 * k as f64 / 200.0;
        let y = [x, x / 2.0, x, x / 2.0];
        assert!(
            c.steps
                .iter()
                .any(|st| (0..4).all(|i| st.apriori[i].contains(y[i]))),
            "contact point at x = {x} outside every step box"
        );
    }
}
