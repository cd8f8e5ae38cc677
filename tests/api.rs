//! The library entry point `ssitrace::intersect` on a scene's two patches gives the same
//! branches, certificates and tolerances as the command line's result document.

use serde_json::Value;
use ssitrace::io::result_json::{enclosures_from_json, result_from_json};
use ssitrace::io::scene::Scene;
use ssitrace::{intersect, Method, Options, SurfaceIntersection};

fn scene_path(file: &str) -> String {
    format!("{}/scenes/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// `ssitrace::intersect` with the options the scene asks for.
fn typed(file: &str) -> SurfaceIntersection {
    let scene = Scene::from_path(std::path::Path::new(&scene_path(file))).expect("scene");
    let opts = Options {
        method: scene.options.method,
        step: scene.options.step,
        required_tolerance: scene.options.required_tolerance,
        ..Options::default()
    };
    let [p, q] = &scene.surfaces;
    intersect(p, q, &opts).expect("runs")
}

/// The result document the command line writes for the scene.
fn cli(file: &str) -> Value {
    let out = std::env::temp_dir().join(format!("ssitrace-api-{}-{file}", std::process::id()));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(scene_path(file))
        .arg("--out")
        .arg(&out)
        .output()
        .expect("the command line runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let doc = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let _ = std::fs::remove_file(&out);
    doc
}

/// Same branches (points bit for bit), same certificates (boxes bit for bit, steps, ends) and
/// same tolerances.
fn same_as_cli(file: &str, branches: usize) {
    let r = typed(file);
    assert_eq!(r.options.method, Method::Both);
    assert!(r.is_complete(), "{file}: search complete");
    assert_eq!(r.branches.len(), branches, "{file}");
    let doc = cli(file);
    let read = result_from_json(&doc).expect("a valid result document");
    assert_eq!(read.intersection, r.marched(), "{file}: marched branches");
    for (k, b) in r.branches.iter().enumerate() {
        assert_eq!(b.id(), k);
        let c = b.certified().expect("certified");
        let json = &doc["branches"][k]["certified"];
        assert_eq!(enclosures_from_json(json).unwrap(), c.boxes, "{file}");
        assert_eq!(json["steps"], c.steps(), "{file}");
        assert_eq!(
            json["tolerance"].as_f64(),
            b.certified_tolerance(),
            "{file}"
        );
        assert_eq!(json["meets_tolerance"], true, "{file}");
        for (e, j) in c.ends.iter().zip(json["end_reasons"].as_array().unwrap()) {
            assert_eq!(j["kind"], e.kind(), "{file}");
        }
        let s = b.straying.as_ref().expect("checked");
        assert!(!s.has_problems(), "{file}: branch {k}");
        assert_eq!(
            json["straying"]["covered_fraction"].as_f64(),
            Some(s.covered_fraction)
        );
    }
    let stats = &doc["stats"];
    let c = r.stats.certify.as_ref().expect("certified");
    assert_eq!(stats["certified_steps"], c.certified_steps);
    assert_eq!(stats["certify_failures"], 0);
    assert_eq!(c.failures, 0);
    assert_eq!(stats["branches"], r.branches.len());
    assert_eq!(stats["points"], r.stats.search.points);
}

#[test]
fn sphere_patch_against_plane_matches_the_command_line() {
    same_as_cli("sphere_patch_plane.json", 1);
}

#[test]
fn two_loops_match_the_command_line() {
    same_as_cli("two_loops_s31_s32.json", 2);
}

/// The options are checked before anything runs.
#[test]
fn bad_options_are_errors() {
    let scene =
        Scene::from_path(std::path::Path::new(&scene_path("sphere_patch_plane.json"))).unwrap();
    let [p, q] = &scene.surfaces;
    for opts in [
        Options {
            step: 0.0,
            ..Options::default()
        },
        Options {
            required_tolerance: f64::NAN,
            ..Options::default()
        },
        Options {
            max_steps: 0,
            ..Options::default()
        },
    ] {
        assert!(intersect(p, q, &opts).is_err());
    }
}

/// `march` traces the same branches and certifies nothing.
#[test]
fn march_only_certifies_nothing() {
    let scene =
        Scene::from_path(std::path::Path::new(&scene_path("sphere_patch_plane.json"))).unwrap();
    let [p, q] = &scene.surfaces;
    let opts = Options {
        method: Method::March,
        step: scene.options.step,
        ..Options::default()
    };
    let r = intersect(p, q, &opts).unwrap();
    assert_eq!(r.branches.len(), 1);
    assert!(r.certificates().is_empty() && r.straying().is_empty());
    assert!(r.stats.certify.is_none() && !r.all_certified());
    assert_eq!(r.marched(), typed("sphere_patch_plane.json").marched());
}

/// Certifying the branches on one thread or on several gives the same branches in the same
/// order, with the same certificates.
#[test]
fn thread_count_does_not_change_the_result() {
    let scene =
        Scene::from_path(std::path::Path::new(&scene_path("two_loops_s31_s32.json"))).unwrap();
    let [p, q] = &scene.surfaces;
    let opts = Options {
        step: scene.options.step,
        ..Options::default()
    };
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| intersect(p, q, &opts).unwrap())
    };
    let (one, three) = (on(1), on(3));
    assert_eq!(one.marched(), three.marched());
    assert_eq!(one.branches.len(), 2);
    for (a, b) in one.branches.iter().zip(&three.branches) {
        let (ca, cb) = (a.certified().unwrap(), b.certified().unwrap());
        assert_eq!(ca.boxes, cb.boxes);
        assert_eq!(ca.ends, cb.ends);
        assert_eq!(a.certified_tolerance(), b.certified_tolerance());
        assert_eq!(a.straying, b.straying);
    }
}
