//! Certified tangential contacts: the tangential ODE tube, its case per step, and the contact
//! cover, checked against closed-form contact curves.

mod common;

use common::scenes::scene;
use common::surfaces::{height_field, SQUARE};
use inari::Interval;
use ssitrace::certify::contact::{
    certify_contact, classify_box, CertifiedContact, ContactEnd, ContactOptions, StepCase,
};
use ssitrace::certify::contact_cover::CoverOptions;
use ssitrace::certify::{certify_branch, CertifyOptions, StepBudget};
use ssitrace::geometry::{Domain, PowerSurface, RationalBezierPatch};
use ssitrace::numeric::scalar::{interval, point};
use std::time::Instant;

/// A 90° arc of the cylinder x² + (z − ½)² = ¼ around its lowest line, along y ∈ [−1, 1]; the
/// middle weight is an interval around √2/2, so the family holds the exact cylinder. It touches
/// z = 0 along x = z = 0, at σ = ½, y = 2t − 1.
fn cylinder() -> RationalBezierPatch {
    let (h, c) = (
        std::f64::consts::FRAC_1_SQRT_2,
        0.5 * std::f64::consts::FRAC_1_SQRT_2,
    );
    let widen = |x: Interval| interval(x.inf() - 1e-15, x.sup() + 1e-15).unwrap();
    let mut pts = Vec::new();
    for (x, z) in [(-c, 0.5 - c), (0.0, 0.5 - h), (c, 0.5 - c)] {
        for y in [-1.0, 1.0] {
            pts.push([point(x), point(y), point(z)].map(widen));
        }
    }
    let w = interval(h.next_down(), h.next_up()).unwrap();
    let weights = vec![point(1.0), point(1.0), w, w, point(1.0), point(1.0)];
    RationalBezierPatch::new([2, 1], pts, Some(weights), Domain::UNIT).unwrap()
}

/// The plane z = 0 over x ∈ [−1, 1], y ∈ [−2, 2] (u = (x + 1)/2, v = (y + 2)/4).
fn plane() -> RationalBezierPatch {
    let pts = [
        [-1.0, -2.0, 0.0],
        [-1.0, 2.0, 0.0],
        [1.0, -2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    RationalBezierPatch::from_f64_points([1, 1], &pts, None, Domain::UNIT).unwrap()
}

/// Q: z = y² + x²/2 + 0.3·x·y (degree 2 × 2).
fn quadratic() -> RationalBezierPatch {
    height_field(SQUARE, vec![(0, 2, 1.0), (2, 0, 0.5), (1, 1, 0.3)])
}

/// P: z = Q + (1 + 0.3·x)·(y − x/2)² (degree 3 × 2): P − Q ≥ 0 vanishes doubly along y = x/2,
/// so they touch along the space parabola (x, x/2, 0.9·x²).
fn cubic() -> RationalBezierPatch {
    height_field(
        SQUARE,
        vec![
            (0, 2, 2.0),
            (2, 0, 0.75),
            (1, 1, -0.7),
            (1, 2, 0.3),
            (2, 1, -0.3),
            (3, 0, 0.075),
        ],
    )
}

fn contains4(b: &[Interval; 4], y: &[f64; 4]) -> bool {
    b.iter().zip(y).all(|(x, v)| x.contains(*v))
}

struct Row {
    name: &'static str,
    r: CertifiedContact,
    secs: f64,
}

fn print_table(rows: &[Row]) {
    println!(
        "{:<22} {:<34} {:>6} {:>10} {:>8} {:>8} {:>10} {:>10} {:>7}",
        "pair",
        "cases (steps)",
        "steps",
        "tube rad",
        "regions",
        "cover",
        "box width",
        "band",
        "time"
    );
    for row in rows {
        let r = &row.r;
        let cases = if r.steps.is_empty() {
            format!("start: {:?}", r.start_case)
        } else {
            r.case_counts()
                .iter()
                .map(|(c, n)| format!("{c:?}×{n}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!(
            "{:<22} {:<34} {:>6} {:>10.2e} {:>8} {:>8} {:>10.2e} {:>10.2e} {:>6.2}s",
            row.name,
            cases,
            r.steps.len(),
            r.tube_radius,
            r.cover.region.len(),
            r.cover.boxes.len(),
            r.cover.max_xyz_width,
            r.cover_band,
            row.secs
        );
    }
}

fn run(
    name: &'static str,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: [f64; 4],
    o: &ContactOptions,
) -> Row {
    let t = Instant::now();
    let r = certify_contact(p, q, y, o).expect("certify_contact");
    Row {
        name,
        r,
        secs: t.elapsed().as_secs_f64(),
    }
}

fn opts(leaf: f64) -> ContactOptions {
    ContactOptions {
        cover: CoverOptions {
            leaf_fraction: leaf,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Checks a traced tangential contact against its closed-form parameter curve `curve(x)`,
/// `x ∈ [lo, hi]`: every step is a tangential curve, both ends reach a boundary, the a-priori
/// boxes and the cover boxes hold every sample, and every tube polynomial lies on the curve
/// within its radius.
fn check_against_curve(
    r: &CertifiedContact,
    curve: impl Fn(f64) -> [f64; 4],
    on_curve: impl Fn(&[f64; 4]) -> f64,
    lo: f64,
    hi: f64,
) {
    assert_eq!(r.start_case, StepCase::TangentialCurve);
    assert!(!r.steps.is_empty());
    assert!(
        r.steps.iter().all(|s| s.case == StepCase::TangentialCurve),
        "{:?}",
        r.case_counts()
    );
    for e in &r.ends {
        assert!(matches!(e, ContactEnd::Boundary { .. }), "{e:?}");
    }
    assert!(r.cover.resolved);
    let n = 2000;
    for k in 0..=n {
        let y = curve(lo + (hi - lo) * k as f64 / n as f64);
        assert!(
            r.steps.iter().any(|s| contains4(&s.apriori, &y)),
            "curve point {y:?} outside the ODE tube"
        );
        assert!(
            r.cover.boxes.iter().any(|b| b.contains(&y)),
            "curve point {y:?} outside the cover"
        );
    }
    for t in &r.tubes {
        for k in 0..=8 {
            let y = t.eval(t.h * k as f64 / 8.0);
            let off = on_curve(&y);
            assert!(
                off <= 4.0 * t.radius_param + 1e-14,
                "tube point {y:?} is {off:e} off the curve (radius {:e})",
                t.radius_param
            );
        }
    }
}

#[test]
fn cylinder_on_plane_is_covered_and_traced_along_its_contact_line() {
    let (p, q) = (cylinder(), plane());
    let line = |t: f64| [0.5, t, 0.5, (2.0 * t + 1.0) / 4.0];
    let off = |y: &[f64; 4]| {
        (y[0] - 0.5)
            .abs()
            .max((y[2] - 0.5).abs())
            .max((y[3] - (2.0 * y[1] + 1.0) / 4.0).abs())
    };
    let row = run("cylinder on plane", &p, &q, line(0.5), &opts(1.0 / 128.0));
    check_against_curve(&row.r, line, off, 0.0, 1.0);
    // The band of kept boxes: every cover box is within a few leaf widths of the line.
    let band = row
        .r
        .cover
        .boxes
        .iter()
        .map(|b| b.xyz[0].mag().max(b.xyz[2].mag()))
        .fold(0.0, f64::max);
    println!("cylinder: cover band |x|, |z| ≤ {band:.3e}");
    assert!(band < 0.1);
    println!("{}", row.r.proven_statement);
    print_table(&[row]);
}

#[test]
fn cubic_quadratic_tangential_contact_is_covered_and_traced() {
    let (p, q) = (cubic(), quadratic());
    let curve = |x: f64| [x, 0.5 * x, x, 0.5 * x];
    let off = |y: &[f64; 4]| {
        (y[1] - 0.5 * y[0])
            .abs()
            .max((y[2] - y[0]).abs())
            .max((y[3] - 0.5 * y[0]).abs())
    };
    let row = run("cubic × quadratic", &p, &q, curve(0.25), &opts(1.0 / 64.0));
    check_against_curve(&row.r, curve, off, -1.0, 1.0);
    // Band: largest model-space distance of a kept box from the parabola (x, x/2, 0.9x²),
    // measured in the closed form (distance to the nearest of dense samples), for the cover
    // above and for finer covers of the same region.
    let band_of = |boxes: &[ssitrace::certify::contact_cover::CoverBox]| {
        boxes
            .iter()
            .map(|b| {
                let c = b.xyz.map(|x| x.mid());
                (0..=4000)
                    .map(|k| {
                        let x = -1.0 + k as f64 / 2000.0;
                        (c[0] - x).powi(2) + (c[1] - 0.5 * x).powi(2) + (c[2] - 0.9 * x * x).powi(2)
                    })
                    .fold(f64::INFINITY, f64::min)
                    .sqrt()
            })
            .fold(0.0, f64::max)
    };
    println!(
        "leaf (param)  regions  kept boxes  max xyz width  band from curve  evaluations  time"
    );
    let mut bands = Vec::new();
    for leaf in [1.0 / 64.0, 1.0 / 128.0] {
        let t = Instant::now();
        let cover = if leaf == 1.0 / 64.0 {
            row.r.cover.clone()
        } else {
            let o = CoverOptions {
                leaf_fraction: leaf,
                ..Default::default()
            };
            // The finer cover on a few region boxes only (its cost grows ≈ 8× per halving).
            let part = &row.r.cover.region[..6];
            ssitrace::certify::contact_cover::contact_cover(&p, &q, part, &o)
        };
        assert!(cover.resolved);
        for k in 0..=1000 {
            let y = curve(-1.0 + k as f64 / 500.0);
            let searched = cover.region.iter().any(|r| contains4(r, &y));
            assert!(
                !searched || cover.boxes.iter().any(|b| b.contains(&y)),
                "{y:?} not covered"
            );
        }
        let band = band_of(&cover.boxes);
        println!(
            "{:>12.4} {:>8} {:>11} {:>14.3e} {:>16.3e} {:>12} {:>5.2}s",
            2.0 * leaf,
            cover.region.len(),
            cover.boxes.len(),
            cover.max_xyz_width,
            band,
            cover.evaluations,
            t.elapsed().as_secs_f64()
        );
        // A few leaf widths: the mean-value exclusion needs a distance ≳ 4 leaf widths (and the
        // searched region, ≈ 3 margins around the tube, caps it).
        assert!(band < 6.0 * 2.0 * leaf, "band {band} for leaf {leaf}");
        bands.push(band);
    }
    let rows = vec![row];
    println!("{}", rows[0].r.proven_statement);
    print_table(&rows);
}

#[test]
fn transversal_pair_is_transversal_on_every_step() {
    // z = x − 0.2 + 0.3 y² crosses z = 0 along x = 0.2 − 0.3 y².
    let p = height_field(SQUARE, vec![(1, 0, 1.0), (0, 0, -0.2), (0, 2, 0.3)]);
    let q = height_field(SQUARE, vec![]);
    let start = [0.2, 0.0, 0.2, 0.0];
    let branch = certify_branch(&p, &q, start, &CertifyOptions::default()).unwrap();
    assert!(!branch.boxes.is_empty());
    for b in &branch.boxes {
        assert_eq!(classify_box(&p, &q, &b.params()), StepCase::Transversal);
    }
    let row = run("transversal crossing", &p, &q, start, &opts(1.0 / 64.0));
    assert_eq!(row.r.start_case, StepCase::Transversal);
    assert!(row.r.steps.is_empty());
    println!(
        "transversal: {} certified boxes, all Transversal",
        branch.boxes.len()
    );
    print_table(&[row]);
}

#[test]
fn sphere_on_plane_is_an_isolated_contact_point() {
    // The unit sphere (inverse stereographic patch) on the plane z = −1, touching at the pole.
    let d = Domain::new(-0.5, 0.5, -0.5, 0.5);
    let sphere = PowerSurface {
        domain: d,
        x: vec![(1, 0, 2.0)],
        y: vec![(0, 1, 2.0)],
        z: vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -1.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0), (0, 2, 1.0)]),
    }
    .to_bezier()
    .unwrap();
    let floor = height_field(d, vec![(0, 0, -1.0)]);
    let row = run(
        "sphere on plane",
        &sphere,
        &floor,
        [0.0; 4],
        &opts(1.0 / 256.0),
    );
    let r = &row.r;
    assert_eq!(r.start_case, StepCase::IsolatedPoint);
    assert!(r.steps.is_empty() && r.ends.iter().all(|e| *e == ContactEnd::NotTraced));
    assert!(r.cover.resolved && r.cover.boxes.iter().any(|b| b.contains(&[0.0; 4])));
    // All kept boxes hug the pole: within a few leaf widths of (0, 0, −1).
    let far = r
        .cover
        .boxes
        .iter()
        .map(|b| {
            b.xyz[0]
                .mag()
                .max(b.xyz[1].mag())
                .max((b.xyz[2] + point(1.0)).mag())
        })
        .fold(0.0, f64::max);
    println!("sphere: kept boxes within {far:.3e} of the pole");
    assert!(far < 0.05);
    print_table(&[row]);
}

#[test]
fn contact_json_holds_the_cover_boxes_bit_for_bit() {
    use ssitrace::io::result_json::{certified_contact_to_json, interval_from_json};
    let d = Domain::new(-0.5, 0.5, -0.5, 0.5);
    // The parabolic cylinder z = x² on z = 0 (polynomial, exact): contact along x = 0.
    let p = height_field(d, vec![(2, 0, 1.0)]);
    let q = height_field(d, vec![]);
    let r = certify_contact(&p, &q, [0.0, 0.0, 0.0, 0.0], &opts(1.0 / 32.0)).unwrap();
    assert!(r.steps.iter().all(|s| s.case == StepCase::TangentialCurve));
    for k in 0..=100 {
        let y = -0.5 + k as f64 / 100.0;
        assert!(r.cover.boxes.iter().any(|b| b.contains(&[0.0, y, 0.0, y])));
    }
    let v = certified_contact_to_json(&r, true);
    let t = &v["tangential"];
    assert_eq!(t["start_case"], "tangential_curve");
    assert_eq!(t["steps"].as_array().unwrap().len(), r.steps.len());
    let boxes = t["cover"]["boxes"].as_array().unwrap();
    assert_eq!(boxes.len(), r.cover.boxes.len());
    for (j, b) in boxes.iter().zip(&r.cover.boxes) {
        for c in 0..3 {
            assert_eq!(interval_from_json(&j["xyz"][c]).unwrap(), b.xyz[c]);
        }
    }
    // The SVG overlay draws the step boxes (merged into at most 4 hulls here), each holding the
    // contact line's points of its steps.
    let mut overlay = ssitrace::io::svg::Overlay::default();
    ssitrace::io::svg::add_contact_boxes(&mut overlay, std::slice::from_ref(&r), 4);
    let expected = r.steps.len().div_ceil(r.steps.len().div_ceil(4));
    assert_eq!(overlay.p_boxes.len(), expected);
    assert_eq!(overlay.xyz_boxes.len(), expected);
    for k in 0..=100 {
        let y = -0.45 + 0.9 * k as f64 / 100.0;
        assert!(
            overlay
                .p_boxes
                .iter()
                .any(|b| b[0][0] <= 0.0 && 0.0 <= b[0][1] && b[1][0] <= y && y <= b[1][1]),
            "contact point (0, {y}) outside the drawn boxes"
        );
    }
}

#[test]
fn scene_contact_events_off_the_line_feed_the_contact_certifier() {
    // The marcher reports this contact as singular events near (not on) the line (its run on
    // this scene takes ≈ 7 s, too slow here): two such events, 1e-9 off the line in t.
    use ssitrace::certify::contact::certify_contact_events;
    use ssitrace::march::branch::{Event, EventKind};
    let scene = scene("cubic_quadratic_tangential.json");
    let (p, q) = (&scene.surfaces[0], &scene.surfaces[1]);
    let event = |x: f64| Event {
        kind: EventKind::Singular,
        p: [x, 0.5 * x + 1e-9],
        q: [x, 0.5 * x],
        xyz: [x, 0.5 * x, 0.9 * x * x],
    };
    let t = Instant::now();
    let base = opts(1.0 / 16.0);
    let o = ContactOptions {
        steps: StepBudget {
            max_steps: 60,
            ..base.steps
        },
        ..base
    };
    let r = certify_contact_events(p, q, &[event(0.3), event(0.31)], &o).unwrap();
    // The second event lies in the first result's searched region: one result.
    assert_eq!(r.len(), 1);
    let first = &r[0];
    assert_eq!(first.start_case, StepCase::TangentialCurve);
    assert!(first
        .steps
        .iter()
        .all(|s| s.case == StepCase::TangentialCurve));
    for t in &first.tubes {
        let y = t.eval(0.0);
        assert!((y[1] - 0.5 * y[0]).abs() < 1e-6, "{y:?}");
    }
    println!(
        "scene events -> {} contact results, first: {} steps, ends {:?}, {:.2}s",
        r.len(),
        first.steps.len(),
        first.ends,
        t.elapsed().as_secs_f64()
    );
}

#[test]
fn contact_that_meets_a_crossing_branch_stops_with_the_case_change() {
    // z = x·y² on z = 0: they touch along y = 0 (doubly), and cross along x = 0. At the origin
    // the contact quadratic vanishes (b11 = b12 = b22 = 0): the tracer must stop there with a
    // reported case, not run through it.
    let p = height_field(SQUARE, vec![(1, 2, 1.0)]);
    let q = height_field(SQUARE, vec![]);
    let row = run(
        "touch meets crossing",
        &p,
        &q,
        [0.5, 0.0, 0.5, 0.0],
        &opts(1.0 / 32.0),
    );
    let r = &row.r;
    assert_eq!(r.start_case, StepCase::TangentialCurve);
    let stops: Vec<_> = r
        .ends
        .iter()
        .filter_map(|e| match e {
            ContactEnd::CaseChanged { case, near } => Some((*case, *near)),
            _ => None,
        })
        .collect();
    assert_eq!(stops.len(), 1, "{:?}", r.ends);
    let (case, near) = stops[0];
    assert_ne!(case, StepCase::TangentialCurve);
    assert!(
        near[0].mag() < 0.1,
        "stopped away from the origin: {near:?}"
    );
    assert!(r
        .ends
        .iter()
        .any(|e| matches!(e, ContactEnd::Boundary { .. })));
    // Every traced step lies on the x > 0 side, and the line y = 0 is traced.
    assert!(r.steps.iter().all(|s| s.apriori[0].sup() > 0.0));
    println!(
        "touch meets crossing: stopped with {case:?} at σ ∈ [{}, {}]",
        near[0].inf(),
        near[0].sup()
    );
    print_table(&[row]);
}
