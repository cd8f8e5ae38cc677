//! From a scene to a result: the top of the pipeline, used by the command line.

use crate::error::{Error, Result};
use crate::io::result_json::ResultMeta;
use crate::io::scene::{Method, Scene};
use crate::marching::intersect::{intersect, IntersectOutcome};
use crate::marching::start_points::SearchOptions;
use crate::marching::MarchOptions;
use serde_json::{json, Map, Value};

/// What to run on a scene (the scene's own options, possibly overridden on the command line).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// The tracing method.
    pub method: Method,
    /// The marching step L.
    pub step: f64,
}

impl RunOptions {
    /// The options a scene asks for.
    pub fn from_scene(scene: &Scene) -> Self {
        RunOptions {
            method: scene.options.method,
            step: scene.options.step,
        }
    }
}

/// Traces every branch of the scene's surface pair with the requested method.
///
/// Errors: a non-positive or non-finite step; a method that is not available yet.
pub fn run_scene(scene: &Scene, opts: &RunOptions) -> Result<(IntersectOutcome, ResultMeta)> {
    if !(opts.step.is_finite() && opts.step > 0.0) {
        return Err(Error::Scene(format!(
            "the step must be a positive number, not {}",
            opts.step
        )));
    }
    if opts.method != Method::March {
        return Err(Error::Scene(format!(
            "method `{}` is not available yet: certified tracing is being built; use `march`",
            opts.method.name()
        )));
    }
    let march = MarchOptions {
        step: opts.step,
        ..MarchOptions::default()
    };
    let [p, q] = &scene.surfaces;
    let outcome = intersect(p, q, &march, &SearchOptions::default());
    let mut meta = ResultMeta::new(scene.options.name.clone(), opts.method.name());
    meta.stats = stats_json(&outcome, opts.step);
    Ok((outcome, meta))
}

fn stats_json(o: &IntersectOutcome, step: f64) -> Map<String, Value> {
    let s = &o.stats;
    let v = json!({
        "step": step,
        "branches": o.intersection.branches.len(),
        "points": s.points,
        "boundary_starts": s.boundary_starts,
        "interior_candidates": s.interior_candidates,
        "skipped_covered": s.skipped_covered,
        "failed_starts": s.failed_starts,
        "undecided_leaves": s.undecided_leaves,
        "search_truncated": s.search_truncated,
        "search_seconds": s.search_seconds,
        "march_seconds": s.march_seconds,
    });
    match v {
        Value::Object(m) => m,
        _ => Map::new(),
    }
}
