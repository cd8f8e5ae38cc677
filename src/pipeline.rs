//! From a scene to a result document, for the command line: the scene's two patches go through
//! [`intersect`] and the result through [`result_meta`]; a shell scene's faces go through
//! [`intersect_shells`] and the result through [`shell_result`].

use crate::error::Result;
use crate::io::intersection_json::{result_meta, shell_result};
use crate::io::result_json::ResultMeta;
use crate::io::scene::{Method, Scene, SceneOptions, ShellScene};
use crate::march::branch::Intersection;
use crate::shell::{intersect_shells, ShellIntersection};
use crate::solve::{intersect, Engine, Options, SurfaceIntersection, DEFAULT_MAX_STEPS};

/// What to run on a scene: the scene's own options, possibly overridden on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// The tracing method.
    pub method: Method,
    /// The certification engine of transversal branches.
    pub engine: Engine,
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
        Self::from_scene_options(&scene.options)
    }

    /// The options a scene's run options ask for (step budget [`DEFAULT_MAX_STEPS`], no tubes).
    pub fn from_scene_options(o: &SceneOptions) -> Self {
        RunOptions {
            method: o.method,
            engine: Engine::default(),
            step: o.step,
            required_tolerance: o.required_tolerance,
            max_steps: DEFAULT_MAX_STEPS,
            tubes: false,
            time_limit: None,
        }
    }

    /// The options of [`intersect`]: these, the rest at their defaults.
    pub fn options(&self) -> Options {
        Options {
            method: self.method,
            engine: self.engine,
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

/// Everything a shell run produced.
#[derive(Debug)]
pub struct ShellRunReport {
    /// The typed result, per traced piece pair.
    pub result: ShellIntersection,
    /// The marched curves of all piece pairs, renumbered into one sequence.
    pub curves: Intersection,
    /// The result document's metadata for `curves` (every branch with its `"pair"`).
    pub meta: ResultMeta,
}

/// Intersects every face of the scene's shell A with every face of shell B
/// ([`intersect_shells`]); the typed result and the merged result document.
///
/// Errors: as [`intersect`].
pub fn run_shells(scene: &ShellScene, opts: &RunOptions) -> Result<ShellRunReport> {
    let [a, b] = &scene.shells;
    let result = intersect_shells(a, b, &opts.options())?;
    let (curves, meta) = shell_result(scene.options.name.clone(), &result, opts.tubes);
    Ok(ShellRunReport {
        result,
        curves,
        meta,
    })
}
