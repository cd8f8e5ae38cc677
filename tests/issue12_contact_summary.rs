//! Issue 12: a tangential contact line is one contact curve in the command line's summary, not
//! dozens of "singular" event lines. The singular events the marcher reports along a certified
//! contact are folded into its line (the result JSON keeps them all).
//!
//! Two contacts: the example scene `cubic_quadratic_tangential.json`, and the graph
//! `z = (x − 0.3y)²(1 + 0.2x)` laid on the plane `z = 0` (tangent along the line `x = 0.3y`)
//! over an asymmetric domain. And a node (two branches crossing) is printed as a crossing, not
//! as a contact curve.

use std::path::{Path, PathBuf};
use std::process::Command;

fn run_cli(scene: &Path, out: &Path) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(scene)
        .args(["--method", "both", "--out"])
        .arg(out)
        .output()
        .expect("the command runs");
    assert!(output.status.success(), "{output:?}");
    String::from_utf8(output.stdout).expect("utf-8")
}

fn check(scene: &Path, tag: &str) {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("issue12_{tag}.json"));
    let text = run_cli(scene, &out);
    println!("{text}");
    let contacts: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("contact "))
        .collect();
    assert_eq!(contacts.len(), 1, "one contact curve: {text}");
    // Named as what is proven: the tangential field's solution (touching is not provable).
    assert!(contacts[0].contains("tangential contact curve (the tangential field's solution"));
    assert!(contacts[0].contains("touching is not provable), certified in"));
    let singular_lines = text
        .lines()
        .filter(|l| l.contains("event Singular"))
        .count();
    assert_eq!(
        singular_lines, 0,
        "events on the contact are folded: {text}"
    );
    // The header's event count is what the contact line says it folded, and the JSON keeps
    // every event.
    let header = text.lines().next().expect("a header");
    let events: usize = header
        .split(", ")
        .find_map(|part| part.strip_suffix(" event(s)"))
        .and_then(|n| n.parse().ok())
        .expect("event count in the header");
    assert!(events > 1, "{header}");
    assert!(
        contacts[0].ends_with(&format!("; {events} singular event(s) on it")),
        "{}",
        contacts[0]
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("result written"))
            .expect("valid JSON");
    let marched_events = json["events"]
        .as_array()
        .map_or(0, |a| a.iter().filter(|e| e["kind"] == "singular").count());
    assert!(marched_events >= events, "JSON keeps the events");
}

#[test]
fn example_tangential_scene_prints_one_contact_curve() {
    let scene =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/cubic_quadratic_tangential.json");
    check(&scene, "example_contact");
}

#[test]
fn own_tangential_pair_prints_one_contact_curve() {
    let text = r#"{"surfaces": [
      {"kind": "polynomial", "domain": [[-0.8, 1.1], [-0.9, 0.7]],
       "x": [[1, 0, 1]], "y": [[0, 1, 1]],
       "z": [[2, 0, 1], [1, 1, -0.6], [0, 2, 0.09], [3, 0, 0.2], [2, 1, -0.12], [1, 2, 0.018]]},
      {"kind": "polynomial", "domain": [[-0.8, 1.1], [-0.9, 0.7]],
       "x": [[1, 0, 1]], "y": [[0, 1, 1]], "z": [[0, 0, 0], [1, 1, 0]]}
    ], "options": {"name": "own-contact", "step": 0.05, "method": "both"}}"#;
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("issue12_own_contact_scene.json");
    std::fs::write(&path, text).expect("scene written");
    check(&path, "own_contact");
}

/// The node of the equal cylinders and of Viviani's pair, certified: the contact line names a
/// crossing of two branches (its start box is proven a branch point and nothing is traced from
/// it), not a "tangential contact curve certified in 0 steps" as it did.
#[test]
fn a_node_is_printed_as_a_crossing_not_a_contact_curve() {
    for name in ["cylinders.json", "viviani.json"] {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(name);
        let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("issue12_node_{name}"));
        let text = run_cli(&path, &out);
        let contacts: Vec<&str> = text
            .lines()
            .filter(|l| l.trim_start().starts_with("contact "))
            .collect();
        assert_eq!(contacts.len(), 1, "{name}: {text}");
        assert!(
            contacts[0].contains("crossing of two branches")
                && !contacts[0].contains("tangential contact curve"),
            "{name}: {}",
            contacts[0]
        );
    }
}
