//! The scene format: parsing, typed errors naming surface and field, round trips, robustness.

mod common;

use common::mangle::replace_at;
use proptest::prelude::*;
use serde_json::{json, Value};
use ssitrace::geometry::Domain;
use ssitrace::io::scene::{Method, Scene, SceneOptions};
use ssitrace::{Error, InputProblem};

/// A valid scene: a rational quarter cylinder (Bézier) and a sphere cap (polynomial with w).
fn valid() -> Value {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    json!({
        "surfaces": [
            {
                "kind": "bezier",
                "degree": [2, 1],
                "points": [[1, 0, 0], [1, 0, 2], [1, 1, 0], [1, 1, 2], [0, 1, 0], [0, 1, 2]],
                "weights": [1, 1, w, w, 1, 1],
                "domain": [[0, 2], [-1, 1]]
            },
            {
                "kind": "polynomial",
                "domain": [[-0.4, 1.0], [0.0, 1.0]],
                "x": [[1, 0, 2]],
                "y": [[0, 1, 2]],
                "z": [[2, 0, 1], [0, 2, 1], [0, 0, -1]],
                "w": [[0, 0, 1], [2, 0, 1], [0, 2, 1]]
            }
        ],
        "options": {"step": 0.01, "method": "both", "tolerance": 1e-10, "name": "cylinder-sphere"}
    })
}

fn parse(v: &Value) -> ssitrace::Result<Scene> {
    Scene::from_json_str(&v.to_string())
}

/// The (surface, field, problem) of an input error; panics on any other outcome.
fn input_error(v: &Value) -> (Option<usize>, String, InputProblem) {
    match parse(v) {
        Err(Error::InvalidInput {
            surface,
            field,
            problem,
        }) => (surface, field, problem),
        other => panic!("expected an input error for {v}, got {other:?}"),
    }
}

/// `valid()` with one edit applied.
fn edited(f: impl FnOnce(&mut Value)) -> Value {
    let mut v = valid();
    f(&mut v);
    v
}

#[test]
fn valid_scene_parses_with_its_options_and_geometry() {
    let scene = parse(&valid()).unwrap();
    assert_eq!(
        scene.options,
        SceneOptions {
            step: 0.01,
            method: Method::Both,
            required_tolerance: 1e-10,
            name: Some("cylinder-sphere".into())
        }
    );
    let [cyl, sphere] = &scene.surfaces;
    assert_eq!(cyl.degree(), [2, 1]);
    assert_eq!(cyl.domain(), Domain::new(0.0, 2.0, -1.0, 1.0));
    // Declared parameters: u = 1 is the middle of the arc, v = 1 the top.
    let p = cyl.point_f64(1.0, 1.0);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((p[0] - h).abs() < 1e-15 && (p[1] - h).abs() < 1e-15 && (p[2] - 2.0).abs() < 1e-15);
    for k in 0..=10 {
        let q = cyl.point_f64(0.2 * k as f64, -1.0 + 0.2 * k as f64);
        assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-14);
    }
    assert_eq!(sphere.degree(), [2, 2]);
    assert_eq!(sphere.domain(), Domain::new(-0.4, 1.0, 0.0, 1.0));
    for (u, v) in [(-0.4, 0.0), (0.3, 0.5), (1.0, 1.0)] {
        let q = sphere.point_f64(u, v);
        // Inverse stereographic projection: (2u, 2v, u²+v²−1)/(1+u²+v²).
        let w = 1.0 + u * u + v * v;
        let e = [2.0 * u / w, 2.0 * v / w, (u * u + v * v - 1.0) / w];
        assert!(
            (0..3).all(|c| (q[c] - e[c]).abs() < 1e-14),
            "{q:?} vs {e:?}"
        );
    }
}

#[test]
fn options_and_optional_fields_have_defaults() {
    let v = json!({"surfaces": [
        {"kind": "bezier", "degree": [1, 1], "points": [[0,0,0],[0,1,0],[1,0,0],[1,1,1]]},
        {"kind": "polynomial", "x": [[1,0,1]], "y": [[0,1,1]], "z": [[1,1,1]]}
    ]});
    let scene = parse(&v).unwrap();
    assert_eq!(scene.options, SceneOptions::default());
    assert_eq!(scene.options.step, 0.05);
    assert_eq!(scene.options.method, Method::Both);
    assert_eq!(scene.options.required_tolerance, 1e-9);
    assert_eq!(scene.surfaces[0].domain(), Domain::UNIT);
    assert_eq!(scene.surfaces[1].domain(), Domain::UNIT);
    // The polynomial z = uv over the unit square equals the bilinear patch of the first surface.
    for (u, v) in [(0.1, 0.9), (0.5, 0.5), (0.7, 0.2)] {
        let a = scene.surfaces[0].point_f64(u, v);
        let b = scene.surfaces[1].point_f64(u, v);
        assert!((0..3).all(|c| (a[c] - b[c]).abs() < 1e-15));
    }
}

#[test]
fn integral_floats_are_accepted_as_degrees_and_exponents() {
    let v = edited(|v| {
        v["surfaces"][0]["degree"] = json!([2.0, 1.0]);
        v["surfaces"][1]["x"] = json!([[1.0, 0.0, 2]]);
    });
    let scene = parse(&v).unwrap();
    assert_eq!(scene, parse(&valid()).unwrap());
    let v = edited(|v| v["surfaces"][0]["degree"] = json!([-3.0, 1]));
    assert_eq!(
        input_error(&v),
        (Some(0), "degree[0]".into(), InputProblem::BadDegree(-3))
    );
}

#[test]
fn intervals_are_accepted_for_coordinates_and_weights() {
    let v = edited(|v| {
        v["surfaces"][0]["points"][0] = json!([[0.99, 1.01], 0, [0, 0.1]]);
        v["surfaces"][0]["weights"][2] = json!([0.7, 0.72]);
    });
    let scene = parse(&v).unwrap();
    let net = scene.surfaces[0].cartesian();
    assert_eq!((net[0][0].inf(), net[0][0].sup()), (0.99, 1.01));
    assert_eq!((net[2][3].inf(), net[2][3].sup()), (0.7, 0.72));
}

#[test]
fn every_bad_input_gives_a_typed_error_naming_surface_and_field() {
    use InputProblem::*;
    let cases: Vec<(Value, Option<usize>, &str, InputProblem)> = vec![
        (
            edited(|v| v["surfaces"][0]["weights"][2] = json!(0)),
            Some(0),
            "weights[2]",
            NonPositiveWeight,
        ),
        (
            edited(|v| v["surfaces"][0]["weights"][4] = json!([-1, 2])),
            Some(0),
            "weights[4]",
            NonPositiveWeight,
        ),
        (
            edited(|v| v["surfaces"][0]["weights"] = json!([1, 1])),
            Some(0),
            "weights",
            WrongCount {
                expected: 6,
                found: 2,
            },
        ),
        (
            edited(|v| {
                v["surfaces"][0]["points"].as_array_mut().unwrap().pop();
            }),
            Some(0),
            "points",
            WrongCount {
                expected: 6,
                found: 5,
            },
        ),
        (
            edited(|v| v["surfaces"][0]["points"][1] = json!([1, 2])),
            Some(0),
            "points[1]",
            WrongCount {
                expected: 3,
                found: 2,
            },
        ),
        (
            edited(|v| v["surfaces"][0]["points"][3][1] = json!([1, 0.5])),
            Some(0),
            "points[3][1]",
            InvertedInterval { lo: 1.0, hi: 0.5 },
        ),
        (
            edited(|v| v["surfaces"][0]["domain"] = json!([[0, 1], [2, -1]])),
            Some(0),
            "domain[1]",
            EmptyDomain { lo: 2.0, hi: -1.0 },
        ),
        (
            edited(|v| v["surfaces"][1]["domain"] = json!([[3, 3], [0, 1]])),
            Some(1),
            "domain[0]",
            EmptyDomain { lo: 3.0, hi: 3.0 },
        ),
        (
            edited(|v| v["surfaces"][0]["degree"] = json!([2, 0])),
            Some(0),
            "degree[1]",
            BadDegree(0),
        ),
        (
            edited(|v| v["surfaces"][0]["degree"] = json!([-2, 1])),
            Some(0),
            "degree[0]",
            BadDegree(-2),
        ),
        (
            edited(|v| v["surfaces"][1]["kind"] = json!("subdivision")),
            Some(1),
            "kind",
            UnknownKind("subdivision".into()),
        ),
        (
            edited(|v| v["surfaces"][1]["colour"] = json!("red")),
            Some(1),
            "colour",
            UnknownField("colour".into()),
        ),
        (
            edited(|v| v["surfaces"][0]["weight"] = json!([1])),
            Some(0),
            "weight",
            UnknownField("weight".into()),
        ),
        (
            edited(|v| v["extra"] = json!(1)),
            None,
            "extra",
            UnknownField("extra".into()),
        ),
        (
            edited(|v| v["options"]["speed"] = json!(1)),
            None,
            "options.speed",
            UnknownField("speed".into()),
        ),
        (
            edited(|v| {
                v["surfaces"][1].as_object_mut().unwrap().remove("z");
            }),
            Some(1),
            "z",
            Missing,
        ),
        (
            edited(|v| {
                v["surfaces"][0].as_object_mut().unwrap().remove("kind");
            }),
            Some(0),
            "kind",
            Missing,
        ),
        (
            edited(|v| {
                v.as_object_mut().unwrap().remove("surfaces");
            }),
            None,
            "surfaces",
            Missing,
        ),
        (
            edited(|v| {
                v["surfaces"].as_array_mut().unwrap().pop();
            }),
            None,
            "surfaces",
            WrongCount {
                expected: 2,
                found: 1,
            },
        ),
        (
            edited(|v| {
                let s = v["surfaces"][0].clone();
                v["surfaces"].as_array_mut().unwrap().push(s);
            }),
            None,
            "surfaces",
            WrongCount {
                expected: 2,
                found: 3,
            },
        ),
        (
            edited(|v| v["surfaces"][1]["x"][0] = json!([-1, 0, 2])),
            Some(1),
            "x[0][0]",
            BadDegree(-1),
        ),
        (
            edited(|v| v["surfaces"][1]["y"][0] = json!([0, 1])),
            Some(1),
            "y[0]",
            WrongCount {
                expected: 3,
                found: 2,
            },
        ),
        (
            // w = u − 0.5 changes sign on the domain.
            edited(|v| v["surfaces"][1]["w"] = json!([[1, 0, 1], [0, 0, -0.5]])),
            Some(1),
            "w",
            NonPositiveWeight,
        ),
        (
            edited(|v| {
                v["surfaces"][0]["points"] = json!(vec![[2, 2, 2]; 6]);
            }),
            Some(0),
            "points",
            Degenerate,
        ),
    ];
    for (v, surface, field, problem) in cases {
        assert_eq!(
            input_error(&v),
            (surface, field.to_string(), problem),
            "scene {v}"
        );
    }
}

#[test]
fn wrong_json_types_are_wrong_shape_errors() {
    let cases: Vec<(Value, Option<usize>, &str)> = vec![
        (
            edited(|v| v["surfaces"] = json!({"a": 1})),
            None,
            "surfaces",
        ),
        (edited(|v| v["surfaces"][1] = json!(3)), Some(1), "surface"),
        (
            edited(|v| v["surfaces"][0]["kind"] = json!(7)),
            Some(0),
            "kind",
        ),
        (
            edited(|v| v["surfaces"][0]["points"] = json!("abc")),
            Some(0),
            "points",
        ),
        (
            edited(|v| v["surfaces"][0]["points"][2][0] = json!("x")),
            Some(0),
            "points[2][0]",
        ),
        (
            edited(|v| v["surfaces"][0]["points"][2][0] = json!([1, 2, 3])),
            Some(0),
            "points[2][0]",
        ),
        (
            edited(|v| v["surfaces"][0]["degree"] = json!([1.5, 1])),
            Some(0),
            "degree[0]",
        ),
        (
            edited(|v| v["surfaces"][0]["domain"] = json!([0, 1])),
            Some(0),
            "domain[0]",
        ),
        (
            edited(|v| v["surfaces"][1]["x"][0][2] = json!(null)),
            Some(1),
            "x[0][2]",
        ),
        (edited(|v| v["options"] = json!([1])), None, "options"),
        (
            edited(|v| v["options"]["step"] = json!("big")),
            None,
            "options.step",
        ),
        (
            edited(|v| v["options"]["step"] = json!(-0.1)),
            None,
            "options.step",
        ),
        (
            edited(|v| v["options"]["tolerance"] = json!(0)),
            None,
            "options.tolerance",
        ),
        (
            edited(|v| v["options"]["method"] = json!("fast")),
            None,
            "options.method",
        ),
        (
            edited(|v| v["options"]["name"] = json!(5)),
            None,
            "options.name",
        ),
    ];
    for (v, surface, field) in cases {
        let (s, f, p) = input_error(&v);
        assert_eq!((s, f.as_str()), (surface, field), "scene {v}");
        assert!(matches!(p, InputProblem::WrongShape(_)), "scene {v}: {p:?}");
    }
}

#[test]
fn top_level_problems_are_scene_errors() {
    for text in [
        "",
        "{",
        "[1, 2]",
        "42",
        "{\"surfaces\": [1e999, 2]}",
        "{\"surfaces\": []} trailing",
    ] {
        match Scene::from_json_str(text) {
            Err(Error::Scene(msg)) => assert!(!msg.is_empty()),
            other => panic!("{text:?}: expected a scene error, got {other:?}"),
        }
    }
}

#[test]
fn files_are_read_and_missing_files_are_io_errors() {
    let dir = std::env::temp_dir().join(format!("ssitrace-scene-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.json");
    std::fs::write(&path, valid().to_string()).unwrap();
    let scene = Scene::from_path(&path).unwrap();
    assert_eq!(scene, parse(&valid()).unwrap());
    let missing = dir.join("missing.json");
    match Scene::from_path(&missing) {
        Err(Error::Io { path, .. }) => assert!(path.ends_with("missing.json")),
        other => panic!("expected an i/o error, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn to_json_round_trips() {
    let scene = parse(&valid()).unwrap();
    let out = scene.to_json();
    assert_eq!(out["surfaces"][0]["kind"], "bezier");
    assert_eq!(out["surfaces"][1]["kind"], "bezier");
    let again = Scene::from_json_value(&out).unwrap();
    // The Bézier surface is written exactly as given.
    assert_eq!(again.surfaces[0], scene.surfaces[0]);
    assert_eq!(again.options, scene.options);
    // The converted polynomial is written as an interval net enclosing the original.
    let (a, b) = (&again.surfaces[1], &scene.surfaces[1]);
    assert_eq!(a.degree(), b.degree());
    assert_eq!(a.domain(), b.domain());
    for (x, y) in a.homogeneous().iter().zip(b.homogeneous()) {
        for c in 0..4 {
            assert!(y[c].subset(x[c]), "{:?} not within {:?}", y[c], x[c]);
            assert!(x[c].wid() < 1e-14);
        }
    }
    // Writing the re-read scene again and re-reading it is stable for the exact surface.
    let third = Scene::from_json_value(&again.to_json()).unwrap();
    assert_eq!(third.surfaces[0], scene.surfaces[0]);
}

/// Arbitrary JSON values, for mangling scenes.
fn arb_json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::from),
        any::<i64>().prop_map(Value::from),
        any::<f64>()
            .prop_map(|x| serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)),
        "[a-z]{0,6}".prop_map(Value::from),
        prop_oneof![Just("bezier"), Just("polynomial"), Just("march")].prop_map(Value::from),
    ];
    leaf.prop_recursive(3, 24, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..5).prop_map(Value::Array),
            prop::collection::btree_map("[a-z]{1,6}", inner, 0..4)
                .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn mangled_json_text_never_panics(
        edits in prop::collection::vec((any::<prop::sample::Index>(), 0u8..3, any::<u8>()), 1..6),
    ) {
        let mut bytes = valid().to_string().into_bytes();
        for (at, op, byte) in edits {
            if bytes.is_empty() {
                break;
            }
            let i = at.index(bytes.len());
            match op {
                0 => { bytes.remove(i); }
                1 => bytes.insert(i, byte),
                _ => bytes[i] = byte,
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        let _ = Scene::from_json_str(&text);
    }

    #[test]
    fn mangled_json_values_never_panic(
        path in prop::collection::vec(any::<usize>(), 0..6),
        new in arb_json(),
    ) {
        let mut v = valid();
        replace_at(&mut v, &path, new);
        match Scene::from_json_value(&v) {
            Ok(scene) => {
                // Whatever was accepted is a valid scene that writes and re-reads.
                prop_assert!(Scene::from_json_value(&scene.to_json()).is_ok());
            }
            Err(Error::InvalidInput { field, .. }) => prop_assert!(!field.is_empty()),
            Err(Error::Scene(_)) => {}
            Err(other) => prop_assert!(false, "unexpected error kind {other:?}"),
        }
    }
}

#[test]
fn absurd_degrees_are_rejected_without_overflow() {
    for deg in [
        json!([u64::MAX, 1]),
        json!([1e14, 1e14]),
        json!([4294967296u64, 4294967296u64]),
    ] {
        let v = edited(|v| v["surfaces"][0]["degree"] = deg.clone());
        let (s, f, _) = input_error(&v);
        assert_eq!(s, Some(0));
        assert!(f == "degree" || f == "points", "{f}");
    }
}
