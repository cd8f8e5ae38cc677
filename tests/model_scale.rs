//! The same model at other sizes: a part 1 000 units across (millimetres) is marched like the
//! same part 50 units across, not with twenty times as many points (the marching step scales
//! with the model beyond 50 units, `Options::step`), and is certified within the same absolute
//! tolerance.

mod common;

use common::scenes::scene;
use ssitrace::geometry::RationalBezierPatch;
use ssitrace::{intersect, Method, Options};

/// `patch` scaled by `k` about the origin (a polynomial patch: its Cartesian control points
/// times `k`).
fn scaled(patch: &RationalBezierPatch, k: f64) -> RationalBezierPatch {
    let points: Vec<[f64; 3]> = patch
        .homogeneous()
        .iter()
        .map(|h| {
            let w = h[3].mid();
            [k * h[0].mid() / w, k * h[1].mid() / w, k * h[2].mid() / w]
        })
        .collect();
    RationalBezierPatch::from_f64_points(patch.degree(), &points, None, patch.domain())
        .expect("a scaled net is valid")
}

#[test]
fn a_part_in_millimetres_is_marched_and_certified_like_the_same_part_twenty_times_smaller() {
    let s = scene("bicubic_transversal.json");
    let [p, q] = &s.surfaces;
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let run = |k: f64| intersect(&scaled(p, k), &scaled(q, k), &opts).expect("valid options");
    let (fifty, thousand) = (run(50.0), run(1000.0));
    assert_eq!(fifty.branches.len(), 1);
    assert_eq!(thousand.branches.len(), 1);
    let points = |r: &ssitrace::SurfaceIntersection| r.branches[0].marched.points.len();
    println!(
        "marched points: {} at 50 units, {} at 1 000 units",
        points(&fifty),
        points(&thousand)
    );
    assert!(
        points(&fifty).abs_diff(points(&thousand)) <= 2,
        "{} vs {}",
        points(&fifty),
        points(&thousand)
    );
    for r in [&fifty, &thousand] {
        let c = r.branches[0].certified().expect("certified");
        assert!(c.certified_tolerance <= opts.required_tolerance);
        assert!(
            c.ends.iter().all(|e| e.kind() == "boundary"),
            "{:?}",
            c.ends
        );
    }
}
