//! Control-point counts and tolerances of the certified B-spline edges (issue 11): the coarse
//! curves have fewer control points than the link-by-link construction they replace (five per
//! link), and their proven tolerance is at most the requested one. Counts are printed
//! (`--nocapture`) for the report.
//!
//! Cases: a torus and the cube against a plane (STEP files written by OpenCASCADE), the NURBS
//! sphere against a plane, and the two loops of Wu, Alessio and Costa's S31/S32 scene.

mod common;

use common::scenes::scene_path;
use ssitrace::edge::{edges_of, edges_of_shells, Edge};
use ssitrace::io::scene::{Scene, ShellScene};
use ssitrace::pipeline::{read_step_scene, run, run_shells, RunOptions};
use std::path::Path;

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Prints and checks one edge: tolerance at most `requested`, fewer control points than the
/// link-by-link construction, p-curves no longer than the 3D curve's part they cover.
fn check(what: &str, e: &Edge, requested: f64) {
    let pc: Vec<usize> = e.pcurves.iter().map(|c| c.curve.points.len()).collect();
    eprintln!(
        "{what}: {} control points ({} links, {} parts; p-curves {pc:?}), tolerance {:.3e} \
         (certified {:.3e}, 3D {:.3e}, fit {:.3e}, cuts {:.3e})",
        e.curve.points.len(),
        e.links,
        e.branches.len(),
        e.edge_tolerance,
        e.bounds.certified_tolerance,
        e.bounds.curve_3d,
        e.bounds.model_fit,
        e.bounds.cuts
    );
    assert!(
        e.edge_tolerance <= requested,
        "{what}: tolerance {:e} above the requested {requested:e}",
        e.edge_tolerance
    );
    assert!(
        e.curve.points.len() < 5 * e.links,
        "{what}: {} control points for {} links",
        e.curve.points.len(),
        e.links
    );
    assert_eq!(
        e.curve.knots.len(),
        e.curve.points.len() + e.curve.degree + 1
    );
    for c in &e.pcurves {
        assert_eq!(
            c.curve.knots.len(),
            c.curve.points.len() + c.curve.degree + 1
        );
        assert!(c.curve.points.len() <= e.curve.points.len());
    }
}

fn shell_edges(what: &str, scene: &ShellScene) -> (Vec<Edge>, f64) {
    let opts = RunOptions::from_scene_options(&scene.options);
    let report = run_shells(scene, &opts).expect("runs");
    let requested = report.result.options.required_tolerance;
    let [a, b] = &scene.shells;
    let edges = edges_of_shells(a, b, &report.result)
        .into_iter()
        .map(|(k, e)| e.unwrap_or_else(|err| panic!("{what}: curve {k}: {err}")))
        .collect();
    (edges, requested)
}

#[test]
fn torus_and_cube_edges_are_coarse_and_within_the_request() {
    // The torus against the plane z = 1/4 (two circles), the sphere against the cube's six
    // faces (eight closed curves of three arcs each).
    for (what, a, b, count) in [
        ("torus", "occt_torus.step", "occt_plane.step", 2),
        ("cube", "occt_sphere.step", "occt_box.step", 8),
    ] {
        let step = read_step_scene(&data(a), &data(b)).expect("reads");
        let (edges, requested) = shell_edges(what, &step.scene);
        assert_eq!(edges.len(), count, "{what}");
        for (k, e) in edges.iter().enumerate() {
            assert!(e.closed);
            check(&format!("{what} curve {k}"), e, requested);
        }
    }
}

#[test]
fn nurbs_sphere_edge_is_coarse_and_within_the_request() {
    let s = ShellScene::from_path(&scene_path("nurbs_sphere_plane.json")).unwrap();
    let (edges, requested) = shell_edges("nurbs sphere", &s);
    assert_eq!(edges.len(), 1);
    check("nurbs sphere / plane", &edges[0], requested);
}

#[test]
fn two_loops_edges_are_coarse_and_within_the_request() {
    let s = Scene::from_path(&scene_path("two_loops_s31_s32.json")).unwrap();
    let opts = RunOptions::from_scene(&s);
    let report = run(&s, &opts).expect("runs");
    let requested = report.result.options.required_tolerance;
    let [p, q] = &s.surfaces;
    let mut made = 0;
    for (k, e) in edges_of(p, q, &report.result) {
        let e = e.unwrap_or_else(|err| panic!("two loops: branch {k}: {err}"));
        check(&format!("two loops branch {k}"), &e, requested);
        made += 1;
    }
    assert!(made >= 2, "two loops: {made} edges");
}

/// A request a hundred times looser takes clearly fewer control points: a degree-8 fit's
/// error falls like the 9th power of its spans, so about 100^(-1/9) ≈ 0.6 times as many; at
/// most 3/4 is asked. (Before knots raised in multiplicity were tried again on more fine spans,
/// S31/S32's first loop took 153 control points at 1e-7 against 161 at 1e-9.)
#[test]
fn a_looser_request_takes_fewer_control_points() {
    let s = Scene::from_path(&scene_path("two_loops_s31_s32.json")).unwrap();
    let [p, q] = &s.surfaces;
    let counts = |tolerance: f64| -> Vec<usize> {
        let opts = RunOptions {
            required_tolerance: tolerance,
            ..RunOptions::from_scene(&s)
        };
        let report = run(&s, &opts).expect("runs");
        edges_of(p, q, &report.result)
            .into_iter()
            .map(|(k, e)| {
                let e = e.unwrap_or_else(|err| panic!("branch {k} at {tolerance:e}: {err}"));
                check(
                    &format!("two loops branch {k} at {tolerance:e}"),
                    &e,
                    tolerance,
                );
                e.curve.points.len()
            })
            .collect()
    };
    let (tight, loose) = (counts(1e-9), counts(1e-7));
    assert_eq!(tight.len(), 2);
    assert_eq!(loose.len(), 2);
    for (t, l) in tight.iter().zip(&loose) {
        assert!(
            4 * l <= 3 * t,
            "{l} control points at 1e-7 against {t} at 1e-9"
        );
    }
}
