//! The command line's summary of a shell scene: one line per joined curve (closed or open,
//! parts, certified tolerance, joins proven and across corners), and the one-point branches a
//! proven corner join covers said to be so instead of failing certification.

use serde_json::{json, Value};
use std::path::Path;
use std::process::Command;

/// A NURBS sphere's great circle through two knot-line crossings of its equator (the plane
/// `y = z`): one closed curve of four parts, two joins across corners, four one-point branches.
#[test]
fn the_summary_names_each_joined_curve_and_the_slivers_its_corners_cover() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenes/nurbs_sphere_plane.json")).unwrap();
    let mut scene: Value = serde_json::from_str(&text).unwrap();
    scene["surfaces"][1] = json!({"kind": "bezier", "degree": [1, 1],
        "points": [[-2.0, -2.0, -2.0], [-2.0, 2.0, 2.0], [2.0, -2.0, -2.0], [2.0, 2.0, 2.0]]});
    scene["options"] = json!({"method": "validated", "name": "great circle"});
    let dir = std::env::temp_dir().join(format!("ssitrace-shell-summary-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("great_circle.json");
    std::fs::write(&path, scene.to_string()).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(&path)
        .output()
        .expect("runs");
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{out}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let curves: Vec<&str> = out.lines().filter(|l| l.starts_with("  curve ")).collect();
    assert_eq!(curves.len(), 1, "{out}");
    assert!(
        curves[0].starts_with("  curve 0: closed, 4 part(s), certified tolerance ")
            && curves[0].ends_with("joins: 4 of 4 proven (2 across corners)"),
        "{out}"
    );
    assert_eq!(out.matches("covered by a proven join").count(), 4, "{out}");
    assert!(!out.contains("FAILED"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}
