//! The cover-chain engine (the default certification) against curves known in closed form,
//! sampled densely: every reported point within the certified tolerance of the true curve,
//! every true point inside the chain's boxes, the chain gap-free; on rotated copies of the
//! scene; against the Taylor engine on the same branch; and with the requested tolerance
//! sizing the links. (Fig. 7's three ellipses are checked the same way in `certified_fig7.rs`,
//! the random pairs against an independent reference in `oracle_random.rs`.)
//!
//! Truth is computed in f64: its error is a few ulps, far below the margins used.

mod common;

use common::rng::Rng;
use common::scenes::scene;
use serde_json::Value;
use ssitrace::certify::{CertifiedBranch, CertifiedEnd, TubePiece};
use ssitrace::io::scene::Scene;
use ssitrace::{intersect, Engine, Method, Options, RationalBezierPatch};

/// Rounding slack of the f64 truth and of evaluating the reported polynomials.
const MARGIN: f64 = 1e-12;

fn certify(s: &Scene, engine: Engine, tolerance: f64) -> Vec<CertifiedBranch> {
    let [p, q] = &s.surfaces;
    let opts = Options {
        method: Method::Validated,
        engine,
        required_tolerance: tolerance,
        ..Options::default()
    };
    let r = intersect(p, q, &opts).expect("runs");
    r.branches
        .iter()
        .map(|b| b.certified().expect("certified").clone())
        .collect()
}

/// Model points of the reported curve, `n` per tube piece.
fn reported(p: &RationalBezierPatch, tubes: &[TubePiece], n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for t in tubes {
        for k in 0..=n {
            let y = t.eval(t.h * k as f64 / n as f64);
            out.push(p.point_f64(y[0], y[1]));
        }
    }
    out
}

fn in_box(b: &[inari::Interval; 3], x: &[f64; 3]) -> bool {
    (0..3).all(|i| b[i].inf() - MARGIN <= x[i] && x[i] <= b[i].sup() + MARGIN)
}

fn apply(r: &[[f64; 3]; 3], x: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| r[i][0] * x[0] + r[i][1] * x[1] + r[i][2] * x[2])
}

fn apply_t(r: &[[f64; 3]; 3], x: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| r[0][i] * x[0] + r[1][i] * x[1] + r[2][i] * x[2])
}

/// The sphere-patch/plane scene with every control point rotated by `r`.
fn rotated_sphere_scene(r: &[[f64; 3]; 3]) -> Scene {
    let path = common::scenes::scene_path("sphere_patch_plane.json");
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    for s in doc["surfaces"].as_array_mut().unwrap() {
        for pt in s["points"].as_array_mut().unwrap() {
            let x: [f64; 3] = std::array::from_fn(|i| pt[i].as_f64().unwrap());
            *pt = serde_json::json!(apply(r, &x));
        }
    }
    Scene::from_json_str(&doc.to_string()).expect("valid scene")
}

/// The circle of the sphere-patch/plane scene: x = 1.375, y² + z² = 141/256 (sphere of radius
/// 1.5625 about the origin). Checks one certificate of it, in the frame rotated by `r`.
fn check_circle(s: &Scene, c: &CertifiedBranch, r: &[[f64; 3]; 3]) {
    let rad = 141f64.sqrt() / 16.0;
    assert_eq!(c.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
    assert!(c.certified_tolerance <= 1e-9, "{}", c.certified_tolerance);
    assert!(!c.arc_length_proven());
    // Gap-free, closed: consecutive boxes share a point, the last meets the first.
    for w in c.boxes.windows(2) {
        assert!(w[0].overlaps(&w[1]), "gap in the chain");
    }
    assert!(c.boxes[c.boxes.len() - 1].overlaps(&c.boxes[0]));
    // Round once: the pieces' lengths add up to the circle's (the loop may be certified as two
    // arcs at the same time; neither may run on past where the other starts).
    let length: f64 = c
        .tubes
        .iter()
        .map(|t| t.along.expect("chain pieces carry their length").arc_length)
        .sum();
    let round = std::f64::consts::TAU * rad;
    assert!(
        (length / round - 1.0).abs() < 1e-3,
        "the pieces are {length} long, the circle {round}"
    );
    // Every reported point within the tolerance of the circle; the angles cover the circle.
    let tol = c.certified_tolerance + MARGIN;
    let mut angles = Vec::new();
    for m in reported(&s.surfaces[0], &c.tubes, 40) {
        let x = apply_t(r, &m);
        let d =
            ((x[0] - 1.375).powi(2) + ((x[1] * x[1] + x[2] * x[2]).sqrt() - rad).powi(2)).sqrt();
        assert!(
            d <= tol,
            "reported point {d:.3e} off the circle (tolerance {tol:.3e})"
        );
        angles.push(x[2].atan2(x[1]));
    }
    angles.sort_by(f64::total_cmp);
    let wrap = angles[0] + std::f64::consts::TAU - angles[angles.len() - 1];
    let gap = angles.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::max);
    assert!(gap < 0.05, "the reported curve leaves a gap of {gap} rad");
    // Every point of the circle lies in a box of the chain.
    let n = 20_000;
    for k in 0..n {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        let x = apply(r, &[1.375, rad * a.cos(), rad * a.sin()]);
        assert!(
            c.boxes.iter().any(|b| in_box(&b.xyz, &x)),
            "circle point at angle {a} is in no box"
        );
    }
}

#[test]
fn sphere_circle_is_a_closed_chain_within_tolerance_both_ways() {
    let s = scene("sphere_patch_plane.json");
    let c = certify(&s, Engine::Chain, 1e-9);
    assert_eq!(c.len(), 1);
    let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    check_circle(&s, &c[0], &id);
}

#[test]
fn rotated_copies_certify_the_rotated_circle() {
    let mut rng = Rng::new(20261202);
    for _ in 0..3 {
        let r = rng.rotation();
        let s = rotated_sphere_scene(&r);
        let c = certify(&s, Engine::Chain, 1e-9);
        assert_eq!(c.len(), 1);
        check_circle(&s, &c[0], &r);
    }
}

#[test]
fn a_looser_tolerance_takes_fewer_links_and_is_met() {
    let s = scene("sphere_patch_plane.json");
    let fine = certify(&s, Engine::Chain, 1e-9);
    let coarse = certify(&s, Engine::Chain, 1e-6);
    assert!(coarse[0].certified_tolerance <= 1e-6);
    assert!(fine[0].certified_tolerance <= 1e-9);
    println!(
        "links: {} at 1e-9, {} at 1e-6",
        fine[0].tubes.len(),
        coarse[0].tubes.len()
    );
    assert!(coarse[0].tubes.len() < fine[0].tubes.len());
}

/// Two unit cylinders at right angles (x² + z² = 1 against y² + z² = 1): the curves lie in the
/// planes x = ±y. Every reported point must satisfy both equations to within the tolerance
/// (each residual is at most twice the distance for points this near a unit cylinder).
#[test]
fn cylinder_branches_lie_on_both_cylinders() {
    let s = scene("cylinders.json");
    let certs = certify(&s, Engine::Chain, 1e-9);
    assert_eq!(certs.len(), 4);
    for c in &certs {
        assert!(c.certified_tolerance <= 1e-9);
        assert!(
            c.ends
                .iter()
                .any(|e| matches!(e, CertifiedEnd::Boundary { .. })),
            "{:?}",
            c.ends
        );
        assert!(
            c.ends
                .iter()
                .any(|e| matches!(e, CertifiedEnd::Singular { .. })),
            "the branch point end is a singular box: {:?}",
            c.ends
        );
        let tol = 2.0 * c.certified_tolerance + MARGIN;
        for m in reported(&s.surfaces[0], &c.tubes, 40) {
            let (a, b) = (
                m[0] * m[0] + m[2] * m[2] - 1.0,
                m[1] * m[1] + m[2] * m[2] - 1.0,
            );
            assert!(
                a.abs() <= tol && b.abs() <= tol,
                "residuals {a:.3e} {b:.3e}"
            );
        }
        for w in c.boxes.windows(2) {
            assert!(w[0].overlaps(&w[1]), "gap in the chain");
        }
    }
}

/// The two engines are independent code: every point the chain reports on the bicubic pair
/// must lie within the chain's tolerance of the Taylor engine's boxes, and the other way round.
#[test]
fn chain_and_taylor_certificates_agree() {
    let s = scene("bicubic_transversal.json");
    let chain = certify(&s, Engine::Chain, 1e-9);
    let taylor = certify(&s, Engine::Taylor, 1e-9);
    assert_eq!((chain.len(), taylor.len()), (1, 1));
    let (c, t) = (&chain[0], &taylor[0]);
    assert_eq!(c.ends, t.ends);
    let near = |boxes: &[ssitrace::certify::EnclosureBox], x: &[f64; 3], slack: f64| {
        boxes.iter().any(|b| {
            (0..3).all(|i| b.xyz[i].inf() - slack <= x[i] && x[i] <= b.xyz[i].sup() + slack)
        })
    };
    let (tc, tt) = (
        c.certified_tolerance + MARGIN,
        t.certified_tolerance + MARGIN,
    );
    for m in reported(&s.surfaces[0], &c.tubes, 20) {
        assert!(
            near(&t.boxes, &m, tc),
            "chain point {m:?} outside the Taylor boxes"
        );
    }
    // The Taylor chain's last steps reach past the domain's boundary; compare inside it.
    let (dp, dq) = (s.surfaces[0].domain(), s.surfaces[1].domain());
    for piece in &t.tubes {
        for k in 0..=4 {
            let y = piece.eval(piece.h * k as f64 / 4.0);
            if !(dp.contains(y[0], y[1], 0.0) && dq.contains(y[2], y[3], 0.0)) {
                continue;
            }
            let m = s.surfaces[0].point_f64(y[0], y[1]);
            assert!(
                near(&c.boxes, &m, tt),
                "Taylor point {m:?} outside the chain boxes"
            );
        }
    }
}

/// A tolerance below rounding cannot be met: the chain still closes the loop, with links kept
/// at rounding level, and says what it proved instead of failing or splitting without end.
#[test]
fn a_tolerance_below_rounding_is_reported_as_not_met() {
    let s = scene("sphere_patch_plane.json");
    let c = certify(&s, Engine::Chain, 1e-300);
    assert_eq!(
        c[0].ends,
        [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]
    );
    let tol = c[0].certified_tolerance;
    assert!(tol > 1e-300 && tol < 1e-12, "{tol}");
    assert!(c[0].tubes.len() < 20_000, "{} links", c[0].tubes.len());
}
