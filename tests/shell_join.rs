//! Joining the branches of a shell intersection across knot lines, seams and shared edges.

use ssitrace::io::scene::ShellScene;
use ssitrace::pipeline::{run_shells, RunOptions};
use ssitrace::shell::{intersect_shells, JoinStatus};
use std::path::PathBuf;

fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

#[test]
fn nurbs_sphere_circle_is_one_closed_curve_of_four_parts() {
    let scene = ShellScene::from_path(&scene_path("nurbs_sphere_plane.json")).unwrap();
    let opts = RunOptions::from_scene_options(&scene.options);
    let report = run_shells(&scene, &opts).unwrap();
    let r = &report.result;
    println!("{:#?}", r.curves);
    assert_eq!(r.curves.len(), 1);
    let c = &r.curves[0];
    assert!(c.closed);
    assert_eq!(c.parts.len(), 4);
    assert!(c.joins.iter().all(|j| j.status == JoinStatus::Proven));
    assert!(c.certified_tolerance.unwrap() <= 1e-9);
    let _ = intersect_shells;
}
