//! Mutation fuzzing of every input reader: the scene reader (Bézier, power-basis and NURBS
//! surfaces, pairs and shells: `ShellScene::from_json_str`, the one the command line uses), the
//! result reader and the STEP reader. Every mutated input must be read or refused with a typed
//! error, never panic.
//!
//! No nightly toolchain (and so no `cargo fuzz`) can be had on the project's machines, so this is
//! a small mutation fuzzer of our own: byte flips, deletions, duplications, splices between
//! inputs and insertions of tokens that break numbers, shapes, kinds and references. Inputs that
//! still read join the corpus, so mutations go deeper than one step. The seeds are the example
//! scenes, NURBS scenes written here (interior knots, unclamped vectors, weights, interval
//! coordinates, shells) and the STEP files of `tests/data/`. CI runs 200 000 scene executions,
//! 20 000 result and 20 000 STEP executions; the long run is one command:
//!
//! ```sh
//! SSITRACE_FUZZ_EXECS=1000000 cargo test --release --test fuzz_readers -- --nocapture
//! ```
//!
//! (`SSITRACE_FUZZ_EXECS` is the scene count; the result and STEP fuzzers run a tenth of it.
//! `SSITRACE_FUZZ_SEED` picks another sequence.) A panicking input is printed in full.

mod common;

use common::rng::Rng;
use ssitrace::io::scene::{Scene, ShellScene};
use ssitrace::io::step::StepModel;
use ssitrace::Error;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Tokens that stress the reader: extreme and non-finite numbers, wrong shapes, other kinds.
const TOKENS: &[&str] = &[
    "1e308",
    "-1e308",
    "1e999",
    "0",
    "-0",
    "5e-324",
    "NaN",
    "-1",
    "99999999999",
    "4294967297",
    "1.5",
    "[",
    "]",
    "{",
    "}",
    ",",
    "null",
    "true",
    "\"x\"",
    "[]",
    "{}",
    "[0, 1]",
    "[1, 0]",
    "[[0, 1], [0, 1]]",
    "\"bezier\"",
    "\"polynomial\"",
    "\"nurbs\"",
    "\"kind\"",
    "\"degree\"",
    "\"points\"",
    "\"weights\"",
    "\"domain\"",
    "\"knots\"",
    "\"surfaces\"",
    "\"options\"",
    "[64, 64]",
    "[1000000, 1000000]",
    "[0, 0, 1e300]",
    "\"step\"",
    "\"method\"",
    "\"march\"",
];

fn mutate(rng: &mut Rng, seeds: &[Vec<u8>], input: &[u8], tokens: &[&str]) -> Vec<u8> {
    let mut out = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let n = out.len().max(1);
        match rng.below(6) {
            0 if !out.is_empty() => {
                let i = rng.below(n);
                out[i] ^= 1 << rng.below(8);
            }
            1 if !out.is_empty() => {
                let i = rng.below(n);
                let len = 1 + rng.below(16);
                out.drain(i..(i + len).min(out.len()));
            }
            2 if !out.is_empty() => {
                let i = rng.below(n);
                let len = 1 + rng.below(32);
                let piece: Vec<u8> = out[i..(i + len).min(out.len())].to_vec();
                let at = rng.below(out.len() + 1);
                out.splice(at..at, piece);
            }
            3 => {
                let other = &seeds[rng.below(seeds.len())];
                let i = rng.below(other.len());
                let len = 1 + rng.below(64);
                let piece = &other[i..(i + len).min(other.len())];
                let at = rng.below(out.len() + 1);
                out.splice(at..at, piece.iter().copied());
            }
            _ => {
                // Replace a number-ish or structural run with a token.
                let tok = tokens[rng.below(tokens.len())].as_bytes();
                let at = rng.below(out.len() + 1);
                let len = rng.below(8).min(out.len() - at);
                out.splice(at..at + len, tok.iter().copied());
            }
        }
    }
    out
}

fn seeds() -> Vec<Vec<u8>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    let mut seeds: Vec<Vec<u8>> = files
        .iter()
        .map(|p| std::fs::read(p).expect("scene"))
        .collect();
    seeds.extend(NURBS_SEEDS.iter().map(|t| t.as_bytes().to_vec()));
    seeds
}

/// NURBS scenes beyond the example: interior knots (four Bézier pieces), an unclamped vector,
/// weights and interval coordinates, and a shell of two faces against a plane.
const NURBS_SEEDS: &[&str] = &[
    r#"{"surfaces": [{"kind": "nurbs", "degree": [2, 2], "knots": [[0, 0, 0, 0.5, 1, 1, 1], [0, 0, 0, 0.5, 1, 1, 1]], "points": [[0, 0, 0], [0, 0.25, 0.1], [0, 0.75, 0.1], [0, 1, 0], [0.25, 0, 0.1], [0.25, 0.25, 0.3], [0.25, 0.75, 0.3], [0.25, 1, 0.1], [0.75, 0, 0.1], [0.75, 0.25, 0.3], [0.75, 0.75, 0.3], [0.75, 1, 0.1], [1, 0, 0], [1, 0.25, 0.1], [1, 0.75, 0.1], [1, 1, 0]]}, {"kind": "bezier", "degree": [1, 1], "points": [[-1, -1, 0.15], [-1, 2, 0.15], [2, -1, 0.15], [2, 2, 0.15]]}]}"#,
    r#"{"surfaces": [{"kind": "nurbs", "degree": [2, 1], "knots": [[0, 1, 2, 3, 4, 5, 6], [0, 0, 1, 1]], "points": [[0, 0, 0], [0, 1, 0], [1, 0, 1], [1, 1, 1], [2, 0, 0], [2, 1, 0], [3, 0, 1], [3, 1, 1]], "weights": [1, 1, [0.7, 0.71], 0.7, 1, 1, 2, 2]}, {"kind": "bezier", "degree": [1, 1], "points": [[0, -1, 0.5], [0, 2, 0.5], [4, -1, [0.5, 0.5000001]], [4, 2, 0.5]]}], "options": {"method": "march"}}"#,
    r#"{"surfaces": [[{"kind": "bezier", "degree": [2, 1], "points": [[1, 0, 0], [1, 0, 1], [1, 1, 0], [1, 1, 1], [0, 1, 0], [0, 1, 1]], "weights": [1, 1, 0.7071067811865476, 0.7071067811865476, 1, 1]}, {"kind": "bezier", "degree": [2, 1], "points": [[0, 1, 0], [0, 1, 1], [-1, 1, 0], [-1, 1, 1], [-1, 0, 0], [-1, 0, 1]], "weights": [1, 1, 0.7071067811865476, 0.7071067811865476, 1, 1]}], {"kind": "bezier", "degree": [1, 1], "points": [[-2, -2, 0.2], [-2, 2, 0.6], [2, -2, 0.4], [2, 2, 0.8]]}]}"#,
];

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_scenes_parse_or_fail_with_a_typed_error() {
    let execs = env_u64("SSITRACE_FUZZ_EXECS", 200_000);
    let mut rng = Rng(env_u64("SSITRACE_FUZZ_SEED", 0x5eed_1234_abcd_0001) | 1);
    let seeds = seeds();
    assert!(
        seeds.len() >= 8,
        "the example scenes and the NURBS scenes are the fuzzer's seeds"
    );
    for (k, seed) in seeds.iter().enumerate() {
        let text = std::str::from_utf8(seed).expect("utf-8");
        assert!(ShellScene::from_json_str(text).is_ok(), "seed {k} reads");
    }
    let (mut ok, mut errors, mut panics) = (0u64, 0u64, Vec::new());
    // Keep a small corpus of inputs that still parse, so mutations go deeper than one step.
    let mut corpus = seeds.clone();
    for _ in 0..execs {
        let base = corpus[rng.below(corpus.len())].clone();
        let input = mutate(&mut rng, &seeds, &base, TOKENS);
        let text = String::from_utf8_lossy(&input).into_owned();
        let read = || ShellScene::from_json_str(&text).map(|s| s.as_pair().is_some());
        match catch_unwind(AssertUnwindSafe(read)) {
            Ok(Ok(_)) => {
                ok += 1;
                if corpus.len() < 256 {
                    corpus.push(input);
                }
            }
            Ok(Err(_)) => errors += 1,
            Err(_) => panics.push(text),
        }
    }
    println!(
        "{execs} executions: {ok} parsed, {errors} typed errors, {} panics",
        panics.len()
    );
    assert!(
        ok > 0 && errors > 0,
        "the mutations must reach both outcomes"
    );
    assert!(panics.is_empty(), "panicking inputs: {panics:#?}");
}

/// The result reader (`result_from_json`, the certified enclosures) on mutated result files of
/// two example scenes, certified with their tubes: parse or typed error, never a panic.
#[test]
fn mutated_results_read_or_fail_with_a_typed_error() {
    use ssitrace::io::result_json::{enclosures_from_json, result_from_json, result_to_json};
    use ssitrace::pipeline::{run, RunOptions};
    let execs = env_u64("SSITRACE_FUZZ_EXECS", 200_000) / 10;
    let mut rng = Rng(env_u64("SSITRACE_FUZZ_SEED", 0x5eed_1234_abcd_0002) | 1);
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let seeds: Vec<Vec<u8>> = ["bicubic_transversal.json", "sphere_patch_plane.json"]
        .iter()
        .map(|name| {
            let text = std::fs::read_to_string(format!("{dir}/{name}")).expect("scene");
            let scene = Scene::from_json_str(&text).expect("valid scene");
            let opts = RunOptions {
                tubes: true,
                ..RunOptions::from_scene(&scene)
            };
            let report = run(&scene, &opts).expect("scene runs");
            let doc = result_to_json(&report.result.marched(), &report.meta);
            serde_json::to_vec(&doc).expect("serialises")
        })
        .collect();
    let read = |text: &str| -> Option<bool> {
        let v: serde_json::Value = serde_json::from_str(text).ok()?;
        let doc = result_from_json(&v).ok()?;
        let certified = v["branches"].as_array().into_iter().flatten();
        let boxes = certified
            .filter_map(|b| b.get("certified"))
            .all(|c| enclosures_from_json(c).is_ok());
        Some(!doc.intersection.branches.is_empty() && boxes)
    };
    assert_eq!(read(std::str::from_utf8(&seeds[0]).unwrap()), Some(true));
    let (mut ok, mut panics) = (0u64, Vec::new());
    for _ in 0..execs {
        let base = &seeds[rng.below(seeds.len())];
        let input = mutate(&mut rng, &seeds, base, TOKENS);
        let text = String::from_utf8_lossy(&input).into_owned();
        match catch_unwind(AssertUnwindSafe(|| read(&text))) {
            Ok(Some(_)) => ok += 1,
            Ok(None) => {}
            Err(_) => panics.push(text),
        }
    }
    println!(
        "{execs} result executions: {ok} read, {} panics",
        panics.len()
    );
    assert!(panics.is_empty(), "panicking inputs: {panics:#?}");
}

/// Tokens that break STEP text: references to missing or odd entities, wrong types, open
/// lists and strings, huge and non-finite numbers.
const STEP_TOKENS: &[&str] = &[
    "#0",
    "#999999",
    "#1",
    "#18446744073709551616",
    "(",
    ")",
    "((",
    "))",
    ",",
    ";",
    "'",
    "''",
    "$",
    "*",
    ".T.",
    ".F.",
    ".UNSPECIFIED.",
    "1.E400",
    "-1.E400",
    "0.",
    "-0.",
    "1E-320",
    "99999999999999999999",
    "4294967297",
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "PLANE",
    "SPHERICAL_SURFACE",
    "CYLINDRICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "CONICAL_SURFACE",
    "AXIS2_PLACEMENT_3D",
    "CARTESIAN_POINT",
    "DIRECTION",
    "ADVANCED_FACE",
    "RATIONAL_B_SPLINE_SURFACE",
    "ENDSEC;",
    "DATA;",
    "/*",
    "*/",
    "=",
];

/// The STEP reader (`StepModel::from_text`, then the faces as NURBS and Bézier pieces) on the
/// mutated files of `tests/data/`: read, or refused with a typed [`Error::Step`], never a panic.
#[test]
fn mutated_step_files_read_or_fail_with_a_typed_error() {
    let execs = env_u64("SSITRACE_FUZZ_EXECS", 200_000) / 10;
    let mut rng = Rng(env_u64("SSITRACE_FUZZ_SEED", 0x5eed_1234_abcd_0003) | 1);
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("tests/data/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "step"))
        .collect();
    files.sort();
    let seeds: Vec<Vec<u8>> = files
        .iter()
        .map(|p| std::fs::read(p).expect("step file"))
        .collect();
    assert!(seeds.len() >= 5, "the OCCT files are the fuzzer's seeds");
    // Read or a typed error; Some(faces) when read.
    let read =
        |text: &str| -> Result<usize, Error> { Ok(StepModel::from_text(text)?.shell()?.len()) };
    let (mut ok, mut errors, mut panics, mut untyped) = (0u64, 0u64, Vec::new(), Vec::new());
    let mut corpus = seeds.clone();
    for _ in 0..execs {
        let base = corpus[rng.below(corpus.len())].clone();
        let input = mutate(&mut rng, &seeds, &base, STEP_TOKENS);
        let text = String::from_utf8_lossy(&input).into_owned();
        match catch_unwind(AssertUnwindSafe(|| read(&text))) {
            Ok(Ok(_)) => {
                ok += 1;
                if corpus.len() < 64 {
                    corpus.push(input);
                }
            }
            Ok(Err(Error::Step { .. })) => errors += 1,
            Ok(Err(e)) => untyped.push(format!("{e}")),
            Err(_) => panics.push(text),
        }
    }
    println!(
        "{execs} STEP executions: {ok} read, {errors} typed errors, {} other errors, {} panics",
        untyped.len(),
        panics.len()
    );
    assert!(
        ok > 0 && errors > 0,
        "the mutations must reach both outcomes"
    );
    assert!(panics.is_empty(), "panicking inputs: {panics:#?}");
    assert!(
        untyped.is_empty(),
        "errors that are not Error::Step: {untyped:#?}"
    );
}
