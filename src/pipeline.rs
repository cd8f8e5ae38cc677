//! From a scene to a result document, for the command line: the scene's two patches go through
//! [`intersect`] and the result through [`result_meta`]; a shell scene's faces go through
//! [`intersect_shells`] and the result through [`shell_result`]. Two STEP files become a shell
//! scene by [`read_step_scene`]; [`mark_step`] adds what they say to the result, and
//! [`step_curves_text`] writes the certified edges back as STEP.

use crate::edge::{BSpline, Edge, EdgeError};
use crate::error::{Error, Result};
use crate::geometry::RationalBezierPatch;
use crate::io::intersection_json::{result_meta, shell_result};
use crate::io::result_json::ResultMeta;
use crate::io::scene::{Method, Scene, SceneOptions, ShellScene};
use crate::io::step::write::{step_text, StepCurve, StepPCurve};
use crate::io::step::StepModel;
use crate::march::branch::Intersection;
use crate::shell::{intersect_shells, Face, ShellIntersection};
use crate::solve::{intersect, Engine, Options, SurfaceIntersection, DEFAULT_MAX_STEPS};
use serde_json::json;
use std::path::Path;
use std::time::Instant;

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

/// [`run`] without the result document's metadata (an empty [`ResultMeta`] with the scene name
/// and method): for a caller that writes no result file, since the metadata of a certified
/// contact (every cover box) or of an unfinished search (every undecided region) takes a
/// noticeable share of a short run to build.
///
/// Errors: as [`run`].
pub fn run_without_meta(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    let [p, q] = &scene.surfaces;
    let result = intersect(p, q, &opts.options())?;
    let meta = ResultMeta::new(scene.options.name.clone(), opts.method.name());
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

/// Two STEP files read as a shell scene ([`read_step_scene`]).
#[derive(Debug, Clone)]
pub struct StepScene {
    /// The faces of each file as a shell, with default options (named after the files).
    pub scene: ShellScene,
    /// What was read from each file.
    pub models: [StepModel; 2],
    /// The two paths.
    pub files: [String; 2],
    /// Wall-clock seconds spent reading both files into shells (parse, NURBS, Bézier split).
    pub read_seconds: f64,
}

/// Whether a path names a STEP file (extension `step` or `stp`, any case).
pub fn is_step_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
}

/// Reads two STEP files ([`StepModel::from_path`]) into a shell scene: every face of `a`
/// against every face of `b`.
///
/// Errors: as [`StepModel::from_path`] and [`StepModel::shell`]; [`Error::Step`] when the two
/// files declare different length units.
pub fn read_step_scene(a: &Path, b: &Path) -> Result<StepScene> {
    let started = Instant::now();
    let ma = StepModel::from_path(a)?;
    let mb = StepModel::from_path(b)?;
    if let (Some(ua), Some(ub)) = (&ma.length_unit, &mb.length_unit) {
        if ua != ub {
            return Err(Error::Step {
                entity: None,
                message: format!(
                    "{} is in {ua} and {} in {ub}: scaling between units is not done",
                    a.display(),
                    b.display()
                ),
            });
        }
    }
    let shells = [ma.shell()?, mb.shell()?];
    let name = |p: &Path| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let scene = ShellScene {
        shells,
        options: SceneOptions {
            name: Some(format!("{} x {}", name(a), name(b))),
            ..SceneOptions::default()
        },
    };
    Ok(StepScene {
        scene,
        models: [ma, mb],
        files: [a.display().to_string(), b.display().to_string()],
        read_seconds: started.elapsed().as_secs_f64(),
    })
}

/// Adds what the STEP files say to a shell result's metadata: every branch and every entry of
/// `stats.pairs` gets `"trimmed"` (whether either face of its pair is trimmed, so that the
/// curve was traced on a surface patch larger than the face) and `"step_faces"` (the two faces'
/// instance numbers); the document gets the member `"step"` (files, length unit, read time,
/// and per file its faces: `entity`, `surface`, `kind`, `trimmed`).
pub fn mark_step(meta: &mut ResultMeta, step: &StepScene) {
    let info = |pair: &serde_json::Value| -> Option<(bool, [u64; 2])> {
        let i = pair.get(0)?.as_u64()? as usize;
        let j = pair.get(1)?.as_u64()? as usize;
        let (fa, fb) = (step.models[0].faces.get(i)?, step.models[1].faces.get(j)?);
        Some((fa.trimmed || fb.trimmed, [fa.entity, fb.entity]))
    };
    for notes in meta.branch_notes.values_mut() {
        if let Some((trimmed, faces)) = notes.get("pair").and_then(info) {
            notes.insert("trimmed".into(), json!(trimmed));
            notes.insert("step_faces".into(), json!(faces));
        }
    }
    if let Some(pairs) = meta.stats.get_mut("pairs").and_then(|p| p.as_array_mut()) {
        for p in pairs {
            if let Some((trimmed, faces)) = p.get("pair").and_then(info) {
                if let Some(m) = p.as_object_mut() {
                    m.insert("trimmed".into(), json!(trimmed));
                    m.insert("step_faces".into(), json!(faces));
                }
            }
        }
    }
    let faces = |m: &StepModel| -> Vec<serde_json::Value> {
        m.faces
            .iter()
            .map(|f| {
                json!({
                    "entity": f.entity,
                    "surface": f.surface_entity,
                    "kind": f.surface_kind,
                    "trimmed": f.trimmed,
                })
            })
            .collect()
    };
    meta.stats
        .insert("read_seconds".into(), json!(step.read_seconds));
    meta.members.insert(
        "step".into(),
        json!({
            "files": step.files,
            "length_unit": step.models[0].length_unit,
            "read_seconds": step.read_seconds,
            "faces": [faces(&step.models[0]), faces(&step.models[1])],
        }),
    );
}

/// The certified edges of a shell run as STEP curves: the text of the file that
/// `--step-out` writes ([`crate::io::step::write::step_text`]), in `length_unit`, and how many
/// curves it holds. Each curve is named with its joined curve's index and the edge's proven
/// tolerance (in full, e.g. `curve 0 tolerance 1.0737e-10`).
///
/// Without `pieces`, one B-spline curve per joined curve that has an edge. With `pieces` (the
/// two shells the edges were made on), one `SURFACE_CURVE` per part of an edge (a stretch on
/// one pair of Bézier pieces, named `curve K part J tolerance T`): the 3D curve over that
/// stretch (its control points and knots, exactly) and the two p-curves, each on its piece
/// written as a rational B-spline surface. An edge whose parts cannot be cut out that way is
/// written whole, without p-curves.
///
/// Errors: as [`crate::io::step::write::step_text`].
pub fn step_curves_text(
    name: &str,
    edges: &[(usize, std::result::Result<Edge, EdgeError>)],
    length_unit: Option<&str>,
    pieces: Option<&[Vec<Face>; 2]>,
) -> Result<(String, usize)> {
    // (label, the part's 3D curve if the edge was cut, the edge, the part's p-curves).
    let mut parts: Vec<(String, Option<BSpline<3>>, &Edge, Vec<PiecePCurve<'_>>)> = Vec::new();
    for (k, e) in edges {
        let Ok(e) = e else { continue };
        let tol = e.edge_tolerance;
        let split = pieces.and_then(|shells| edge_parts(e, shells));
        match split {
            Some(ps) => {
                for (j, (sub, pcs)) in ps.into_iter().enumerate() {
                    parts.push((
                        format!("curve {k} part {j} tolerance {tol:e}"),
                        Some(sub),
                        e,
                        pcs,
                    ));
                }
            }
            None => parts.push((format!("curve {k} tolerance {tol:e}"), None, e, Vec::new())),
        }
    }
    let curves: Vec<StepCurve<'_>> = parts
        .iter()
        .map(|(label, sub, e, pcs)| StepCurve {
            label: label.clone(),
            curve: sub.as_ref().unwrap_or(&e.curve),
            pcurves: pcs
                .iter()
                .map(|&(piece, curve)| StepPCurve { piece, curve })
                .collect(),
        })
        .collect();
    let worst = edges
        .iter()
        .filter_map(|(_, e)| e.as_ref().ok().map(|e| e.edge_tolerance))
        .fold(1e-7_f64, f64::max);
    Ok((step_text(name, &curves, length_unit, worst)?, curves.len()))
}

/// A p-curve and the Bézier piece it lies on.
type PiecePCurve<'a> = (&'a RationalBezierPatch, &'a BSpline<2>);

/// One part of an edge: its 3D curve and its p-curves.
type EdgePart<'a> = (BSpline<3>, Vec<PiecePCurve<'a>>);

/// An edge cut into its parts: per part the 3D curve over the part's range and its p-curves
/// with their pieces; `None` if a p-curve's piece is missing or its knots are not a stretch of
/// the 3D curve's.
fn edge_parts<'a>(e: &'a Edge, shells: &'a [Vec<Face>; 2]) -> Option<Vec<EdgePart<'a>>> {
    let mut out: Vec<EdgePart<'a>> = Vec::new();
    let mut last: Option<(usize, [f64; 2])> = None;
    for pc in &e.pcurves {
        let piece = shells
            .get(pc.surface)?
            .get(pc.face)?
            .pieces()
            .get(pc.piece)?;
        let key = (pc.branch, pc.curve.range());
        if last != Some(key) {
            out.push((sub_curve(&e.curve, &pc.curve)?, Vec::new()));
            last = Some(key);
        }
        out.last_mut()?.1.push((piece, &pc.curve));
    }
    (!out.is_empty()).then_some(out)
}

/// The stretch of `c` on the knots of `like` (whose knots are a clamped stretch of `c`'s, at
/// knots of full multiplicity), exactly.
fn sub_curve(c: &BSpline<3>, like: &BSpline<2>) -> Option<BSpline<3>> {
    let p = c.degree;
    let n = like.points.len();
    if like.degree != p || n < 2 || like.knots.len() != n + p + 1 {
        return None;
    }
    let s0 = like.knots[0];
    let start = c
        .knots
        .iter()
        .filter(|&&t| t < s0)
        .count()
        .saturating_sub(1);
    if start + n > c.points.len() || c.knots.get(start + 1..start + n + p)? != &like.knots[1..n + p]
    {
        return None;
    }
    Some(BSpline {
        degree: p,
        knots: like.knots.clone(),
        points: c.points[start..start + n].to_vec(),
    })
}
