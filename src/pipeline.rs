//! From a scene to a result document, for the command line: the scene's two patches go through
//! [`intersect`] and the result through [`result_meta`].

use crate::error::Result;
use crate::io::intersection_json::result_meta;
use crate::io::result_json::ResultMeta;
use crate::io::scene::{Method, Scene};
use crate::solve::{intersect, Options, SurfaceIntersection, DEFAULT_MAX_STEPS};

/// What to run on a scene: the scene's own options, possibly overridden on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// The tracing method.
    pub method: Method,
    /// The marching step L.
    pub step: f64,
    /// The model-space tolerance a certified branch should meet (reported, not enforced).
    pub required_tolerance: f64,
    /// Certified step budget per half branch.
    pub max_steps: usize,
    /// Write the certified tube pieces into the result (large).
    pub tubes: bool,
    /// Wall-clock limit of the certification ([`Options::time_limit`]).
    pub time_limit: Option<std::time::Duration>,
}

impl RunOptions {
    /// The options a scene asks for (step budget [`DEFAULT_MAX_STEPS`], no tubes).
    pub fn from_scene(scene: &Scene) -> Self {
        RunOptions {
            method: scene.options.method,
            step: scene.options.step,
            required_tolerance: scene.options.required_tolerance,
            max_steps: DEFAULT_MAX_STEPS,
            tubes: false,
            time_limit: None,
        }
    }

    /// The options of [`intersect`]: these, the rest at their defaults.
    pub fn options(&self) -> Options {
        Options {
            method: self.method,
            step: self.step,
            required_tolerance: self.required_tolerance,
            max_steps: self.max_steps,
            time_limit: self.time_limit,
            ..Options::default()
        }
    }
}

/// Everything a run produced.
#[derive(Debug)]
pub struct RunReport {
    /// The typed result.
    pub result: SurfaceIntersection,
    /// Scene name, method, stats and the certified members, ready for the result JSON (with
    /// the marched curves, [`SurfaceIntersection::marched`]).
    pub meta: ResultMeta,
}

/// Traces every branch of the scene's surface pair with the requested method; the typed result
/// and the result document's metadata.
///
/// Errors: as [`intersect`] (a non-positive or non-finite step or tolerance, a zero step
/// budget). A branch whose certification fails is not an error of the run.
pub fn run(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    let [p, q] = &scene.surfaces;
    let result = intersect(p, q, &opts.options())?;
    let meta = result_meta(scene.options.name.clone(), &result, opts.tubes);
    Ok(RunReport { result, meta })
}

/// [`run`], as a pair.
pub fn run_scene(scene: &Scene, opts: &RunOptions) -> Result<(SurfaceIntersection, ResultMeta)> {
    let report = run(scene, opts)?;
    Ok((report.result, report.meta))
}
