//! The command line on STEP files: `ssitrace trace A.step B.step --out … --step-out …`, the
//! result's per-pair `"trimmed"`, and a malformed file's typed error (exit code 2, no panic).

use std::path::{Path, PathBuf};
use std::process::Command;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ssitrace-step-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn trace_two_step_files_writes_result_and_step_curves() {
    let (out, step_out) = (tmp("r.json"), tmp("c.step"));
    let run = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(data("occt_sphere.step"))
        .arg(data("occt_plane.step"))
        .arg("--out")
        .arg(&out)
        .arg("--step-out")
        .arg(&step_out)
        .output()
        .expect("runs");
    let said = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{said}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(said.contains("SPHERICAL_SURFACE"), "{said}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let branches = doc["branches"].as_array().unwrap();
    assert!(!branches.is_empty());
    for b in branches {
        assert_eq!(
            b["trimmed"],
            serde_json::json!(true),
            "the plane face is trimmed"
        );
        assert!(b["pair"].is_array());
    }
    assert_eq!(doc["step"]["faces"][0][0]["kind"], "SPHERICAL_SURFACE");
    assert_eq!(doc["step"]["faces"][0][0]["trimmed"], false);
    assert_eq!(doc["step"]["faces"][1][0]["trimmed"], true);
    for p in doc["stats"]["pairs"].as_array().unwrap() {
        assert!(p["trimmed"].is_boolean());
    }
    let text = std::fs::read_to_string(&step_out).unwrap();
    let curves = ssitrace::io::step::write::read_step_curves(&text).unwrap();
    assert_eq!(curves.len(), 1);
    let _ = std::fs::remove_file(&out);
    let _ = std::fs::remove_file(&step_out);
}

#[test]
fn malformed_step_file_is_a_typed_error() {
    let bad = tmp("bad.step");
    let t = std::fs::read_to_string(data("occt_sphere.step")).unwrap();
    std::fs::write(&bad, t.replacen("#23,1.)", "#23,-1.)", 1)).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(&bad)
        .arg(data("occt_plane.step"))
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("STEP entity #22"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // A STEP file needs a second one.
    let run = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(data("occt_sphere.step"))
        .output()
        .expect("runs");
    assert_eq!(run.status.code(), Some(2));
    let _ = std::fs::remove_file(&bad);
}

/// `--step-pcurves` on a two-patch JSON scene: the curve written as SURFACE_CURVEs with two
/// PCURVEs each, on the patches written as B-spline surfaces.
#[test]
fn step_pcurves_on_a_json_scene() {
    let out = tmp("pc.step");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/sphere_patch_plane.json");
    let run = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(&scene)
        .arg("--step-out")
        .arg(&out)
        .arg("--step-pcurves")
        .output()
        .expect("runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let surface_curves = text.matches("SURFACE_CURVE(").count();
    assert!(surface_curves >= 1, "{text}");
    assert_eq!(text.matches("= PCURVE(").count(), 2 * surface_curves);
    assert_eq!(text.matches("RATIONAL_B_SPLINE_SURFACE(").count(), 2);
    let file = ssitrace::io::step::part21::parse(&text).expect("parses");
    assert!(!file.instances.is_empty());
    let _ = std::fs::remove_file(&out);
}
