//! From a scene to a result: the top of the pipeline, used by the command line.
//!
//! `march` traces every branch with the floating-point marcher. `validated` and `both` march
//! first (to find the branches) and then certify each branch from one of its points with
//! [`certify_branch`], within step and arc-length budgets; a branch whose certification fails
//! is reported as failed, the run goes on. The marched polylines are then checked against the
//! certificates ([`check_branches`]): straying points, looping, unchecked points and the covered
//! fraction go into each branch's `"certified"` member as `"straying"` and into the stats.

use std::time::Instant;

use crate::certify::contact::{certify_contact_events, CertifiedContact, ContactOptions};
use crate::certify::contact_cover::CoverOptions;
use crate::certify::{certify_branch, CertifiedBranch, CertifyOptions, StepBudget};
use crate::check::straying::{check_branches, StrayReport};
use crate::error::{Error, Result};
use crate::geometry::RationalBezierPatch;
use crate::io::result_json::{
    certified_contact_to_json, certified_error_to_json, certified_events_to_json,
    certified_to_json, ResultMeta, CERTIFIED_CONTACT_EVENT,
};
use crate::io::scene::{Method, Scene};
use crate::io::topology_json::{boundary_ends_to_json, node_to_json};
use crate::march::branch::Branch;
use crate::march::branch::EventKind;
use crate::march::MarchOptions;
use crate::pair::boundary_direction::BoundaryOptions;
use crate::search::start_points::SearchOptions;
use crate::topology::branch_ends::check_branch_ends;
use crate::topology::intersect::{intersect, IntersectOutcome};
use inari::Interval;
use serde_json::{json, Map, Value};

/// Default certified step budget per half branch.
pub const DEFAULT_MAX_STEPS: usize = 20_000;

/// The arc-length budget of a certified half branch, as a multiple of the marched length.
pub const LENGTH_BUDGET_FACTOR: f64 = 1.5;

/// What to run on a scene (the scene's own options, possibly overridden on the command line).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// The tracing method.
    pub method: Method,
    /// The marching step L.
    pub step: f64,
    /// The required tolerance: the model-space tolerance a certified branch should meet
    /// (reported, not enforced).
    pub required_tolerance: f64,
    /// Certified step budget per half branch.
    pub max_steps: usize,
    /// Write the certified tube pieces into the result (large).
    pub tubes: bool,
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
        }
    }
}

/// The certification of one marched branch.
#[derive(Debug)]
pub struct BranchCertificate {
    /// The id of the marched branch.
    pub branch: usize,
    /// The marched point `(σ, t, u, v)` the certified trace started from.
    pub start: [f64; 4],
    /// The arc-length budget per half branch that was given.
    pub max_length: f64,
    /// The certified branch, or why it could not be certified.
    pub result: Result<CertifiedBranch>,
    /// Wall-clock seconds spent.
    pub seconds: f64,
}

impl BranchCertificate {
    /// Whether the certified tolerance is at most `tolerance`; `None` when certification failed.
    pub fn meets(&self, tolerance: f64) -> Option<bool> {
        self.result
            .as_ref()
            .ok()
            .map(|c| c.certified_tolerance <= tolerance)
    }
}

/// Everything a run produced.
#[derive(Debug)]
pub struct RunReport {
    /// The marched branches and events, with search statistics.
    pub outcome: IntersectOutcome,
    /// Scene name, method, stats and the certified members, ready for the result JSON.
    pub meta: ResultMeta,
    /// One entry per marched branch, in branch order, when the method certifies; else empty.
    pub certificates: Vec<BranchCertificate>,
    /// The straying check of each marched branch against the certificates, in branch order,
    /// when the method certifies; else empty.
    pub straying: Vec<StrayReport>,
    /// The tangential contacts certified from the marcher's contact events, when the method
    /// certifies; else empty.
    pub contacts: Vec<CertifiedContact>,
    /// Wall-clock seconds of the marching stage (start-point search and marching).
    pub march_seconds: f64,
    /// Wall-clock seconds of all certification (0 for `march`).
    pub certify_seconds: f64,
}

/// Traces every branch of the scene's surface pair with the requested method.
///
/// Errors: a non-positive or non-finite step or tolerance; a zero step budget. A branch whose
/// certification fails is not an error of the run (see [`run`]).
pub fn run_scene(scene: &Scene, opts: &RunOptions) -> Result<(IntersectOutcome, ResultMeta)> {
    let report = run(scene, opts)?;
    Ok((report.outcome, report.meta))
}

/// Runs the requested method and keeps everything: the marched outcome, the result metadata
/// (with a `"certified"` member per branch and the certified events when the method
/// certifies) and the certificates themselves.
///
/// Errors: as [`run_scene`].
pub fn run(scene: &Scene, opts: &RunOptions) -> Result<RunReport> {
    if !(opts.step.is_finite() && opts.step > 0.0) {
        return Err(Error::Scene(format!(
            "the step must be a positive number, not {}",
            opts.step
        )));
    }
    if !(opts.required_tolerance.is_finite() && opts.required_tolerance > 0.0) {
        return Err(Error::Scene(format!(
            "the tolerance must be a positive number, not {}",
            opts.required_tolerance
        )));
    }
    if opts.max_steps == 0 {
        return Err(Error::Scene("the step budget must be at least 1".into()));
    }
    let march = MarchOptions {
        step: opts.step,
        ..MarchOptions::default()
    };
    let [p, q] = &scene.surfaces;
    let started = Instant::now();
    let outcome = intersect(p, q, &march, &SearchOptions::default());
    let march_seconds = started.elapsed().as_secs_f64();
    let mut meta = ResultMeta::new(scene.options.name.clone(), opts.method.name());
    meta.stats = stats_json(&outcome, opts.step);
    annotate_topology(p, q, &outcome, &mut meta);
    let mut certificates = Vec::new();
    let mut straying = Vec::new();
    let mut contacts = Vec::new();
    let mut certify_seconds = 0.0;
    if opts.method != Method::March {
        for b in &outcome.intersection.branches {
            let cert = certify_marched_branch(p, q, b, opts);
            certify_seconds += cert.seconds;
            meta.certified.insert(
                b.id,
                certificate_json(&cert, opts.required_tolerance, opts.tubes),
            );
            if let Ok(c) = &cert.result {
                meta.certified_events
                    .extend(certified_events_to_json(b.id, c, &|y| model_box(p, q, y)));
            }
            certificates.push(cert);
        }
        let steps: usize = certificates
            .iter()
            .filter_map(|c| c.result.as_ref().ok())
            .map(|c| c.steps())
            .sum();
        let failed = certificates.iter().filter(|c| c.result.is_err()).count();
        meta.stats.insert("certified_steps".into(), json!(steps));
        meta.stats.insert("certify_failures".into(), json!(failed));
        meta.stats
            .insert("certify_seconds".into(), json!(certify_seconds));
        meta.stats.insert("max_steps".into(), json!(opts.max_steps));
        meta.stats
            .insert("tolerance".into(), json!(opts.required_tolerance));
        let certified: Vec<Option<&CertifiedBranch>> = certificates
            .iter()
            .map(|c| c.result.as_ref().ok())
            .collect();
        let checking = Instant::now();
        straying = check_branches(
            p,
            q,
            &outcome.intersection.branches,
            &certified,
            march.newton_tolerance,
        );
        meta.stats.insert(
            "straying_seconds".into(),
            json!(checking.elapsed().as_secs_f64()),
        );
        let contacting = Instant::now();
        contacts = certify_contacts(p, q, &outcome, opts.tubes, &mut meta);
        meta.stats.insert(
            "contact_seconds".into(),
            json!(contacting.elapsed().as_secs_f64()),
        );
        for r in &straying {
            if let Some(Value::Object(m)) = meta.certified.get_mut(&r.branch) {
                m.insert("straying".into(), straying_json(r));
            }
        }
        let count = |f: &dyn Fn(&StrayReport) -> usize| straying.iter().map(f).sum::<usize>();
        meta.stats.insert(
            "straying_points".into(),
            json!(count(&|r| r.straying.len())),
        );
        meta.stats.insert(
            "unchecked_points".into(),
            json!(count(&|r| r.unchecked.len())),
        );
        meta.stats.insert(
            "looping_branches".into(),
            json!(count(&|r| usize::from(r.looping))),
        );
    }
    Ok(RunReport {
        outcome,
        meta,
        certificates,
        straying,
        contacts,
        march_seconds,
        certify_seconds,
    })
}

/// Writes the topology notes of a marched outcome into `meta`: each branch's boundary ends
/// checked by Grandine's test (`"boundary_ends"`, with the count of inconsistent ends in the
/// stats as `"inconsistent_boundary_ends"`), and each singular event's graph node (`"node"`).
fn annotate_topology(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    outcome: &IntersectOutcome,
    meta: &mut ResultMeta,
) {
    let mut inconsistent = 0;
    for b in &outcome.intersection.branches {
        let checks = check_branch_ends(p, q, b, &BoundaryOptions::default());
        if checks.is_empty() {
            continue;
        }
        inconsistent += checks
            .iter()
            .flatten()
            .flatten()
            .filter(|c| !c.consistent)
            .count();
        meta.branch_notes
            .entry(b.id)
            .or_default()
            .insert("boundary_ends".into(), boundary_ends_to_json(&checks));
    }
    meta.stats
        .insert("inconsistent_boundary_ends".into(), json!(inconsistent));
    for (k, e) in outcome.intersection.events.iter().enumerate() {
        if e.kind != EventKind::Singular {
            continue;
        }
        let node = outcome.nodes.iter().find(|n| {
            let d2: f64 = (0..3).map(|i| (n.xyz[i] - e.xyz[i]).powi(2)).sum();
            d2 <= 1e-12 * (1.0 + e.xyz.iter().map(|x| x * x).sum::<f64>())
        });
        if let Some(n) = node {
            meta.event_notes
                .entry(k)
                .or_default()
                .insert("node".into(), node_to_json(n));
        }
    }
}

/// Leaf size of the contact cover in a run, as a fraction of each domain width.
pub const PIPELINE_COVER_LEAF: f64 = 1.0 / 64.0;
/// Enclosure budget of the contact cover in a run (when spent, the cover stays sound but coarse).
pub const PIPELINE_COVER_EVALUATIONS: usize = 50_000;

/// Certifies the tangential contacts behind the marcher's contact (`Singular`) events with
/// [`certify_contact_events`] and appends one `"tangential_contact"` event per contact to the
/// certified events (or one with an `"error"` if certification failed).
fn certify_contacts(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    outcome: &IntersectOutcome,
    tubes: bool,
    meta: &mut ResultMeta,
) -> Vec<CertifiedContact> {
    let events = &outcome.intersection.events;
    // A coarser cover than the library default: still sound (every intersection point of the
    // searched region lies in a kept box), at a fraction of the cost.
    let opts = ContactOptions {
        cover: CoverOptions {
            leaf_fraction: PIPELINE_COVER_LEAF,
            max_evaluations: PIPELINE_COVER_EVALUATIONS,
        },
        ..ContactOptions::default()
    };
    match certify_contact_events(p, q, events, &opts) {
        Ok(contacts) => {
            for c in &contacts {
                let mut v = certified_contact_to_json(c, tubes);
                if let Value::Object(m) = &mut v {
                    m.insert("kind".into(), json!(CERTIFIED_CONTACT_EVENT));
                }
                meta.certified_events.push(v);
            }
            meta.stats
                .insert("certified_contacts".into(), json!(contacts.len()));
            contacts
        }
        Err(e) => {
            meta.certified_events.push(json!({
                "kind": CERTIFIED_CONTACT_EVENT,
                "error": e.to_string(),
            }));
            Vec::new()
        }
    }
}

/// `sin²` of the angle between the normals of P and Q at `y`: 1 for perpendicular surfaces,
/// 0 at tangency (a floating-point estimate, used only to pick a start point).
fn transversality(p: &RationalBezierPatch, q: &RationalBezierPatch, y: &[f64; 4]) -> f64 {
    let (a, b) = (p.derivs_f64(y[0], y[1]), q.derivs_f64(y[2], y[3]));
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let n2 = |u: [f64; 3]| u.iter().map(|x| x * x).sum::<f64>();
    let (np, nq) = (cross(a.su, a.sv), cross(b.su, b.sv));
    let s = n2(cross(np, nq)) / (n2(np) * n2(nq));
    if s.is_finite() {
        s
    } else {
        0.0
    }
}

/// The start point of a certified trace: the middle point of the marched branch, unless a point
/// at a quarter or a third of the way is at least twice as transversal.
fn choose_start(p: &RationalBezierPatch, q: &RationalBezierPatch, b: &Branch) -> Option<[f64; 4]> {
    let n = b.points.len();
    if n == 0 {
        return None;
    }
    let at = |i: usize| {
        let c = &b.points[i.min(n - 1)];
        [c.p[0], c.p[1], c.q[0], c.q[1]]
    };
    let middle = at(n / 2);
    let mut best = (middle, 2.0 * transversality(p, q, &middle));
    for i in [n / 4, n / 3, 2 * n / 3, 3 * n / 4] {
        let y = at(i);
        let s = transversality(p, q, &y);
        if s > best.1 {
            best = (y, s);
        }
    }
    Some(best.0)
}

/// Certifies one marched branch within the budgets of `opts`: from its middle point (or a more
/// transversal point at a quarter or a third of the way), with `opts.max_steps` steps and
/// [`LENGTH_BUDGET_FACTOR`] × the marched length of arc per half branch. Never fails as a
/// whole: a certification failure is kept in [`BranchCertificate::result`].
pub fn certify_marched_branch(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &Branch,
    opts: &RunOptions,
) -> BranchCertificate {
    let started = Instant::now();
    let length = b.length();
    // A closed loop is traced once from its start, an open branch each way from the middle:
    // 1.5 × the marched length covers either with room to spare.
    let max_length = if length > 0.0 {
        LENGTH_BUDGET_FACTOR * length
    } else {
        opts.step
    };
    let certify = CertifyOptions {
        steps: StepBudget {
            max_steps: opts.max_steps,
            max_length,
            ..StepBudget::CERTIFY
        },
        ..CertifyOptions::default()
    };
    let (start, result) = match choose_start(p, q, b) {
        Some(y) => (y, certify_branch(p, q, y, &certify)),
        None => (
            [f64::NAN; 4],
            Err(Error::Certification {
                reason: "the marched branch has no points".into(),
                near: [f64::NAN; 4],
            }),
        ),
    };
    BranchCertificate {
        branch: b.id,
        start,
        max_length,
        result,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// The branch's `"certified"` object: [`certified_to_json`] (or `{"error": ...}`) plus
/// `"meets_tolerance"` (only when certified), `"required_tolerance"`, `"start_point"` (when the
/// branch had points), `"max_length"` and `"seconds"`.
pub fn certificate_json(c: &BranchCertificate, tolerance: f64, tubes: bool) -> Value {
    let mut v = match &c.result {
        Ok(cb) => certified_to_json(cb, tubes),
        Err(e) => certified_error_to_json(e),
    };
    if let Value::Object(m) = &mut v {
        if let Some(ok) = c.meets(tolerance) {
            m.insert("meets_tolerance".into(), json!(ok));
        }
        m.insert("required_tolerance".into(), json!(tolerance));
        if c.start.iter().all(|x| x.is_finite()) {
            m.insert("start_point".into(), json!(c.start));
        }
        m.insert("max_length".into(), json!(c.max_length));
        m.insert("seconds".into(), json!(c.seconds));
    }
    v
}

/// A branch's `"straying"` object: `straying_points` (objects with the marched point's `index`,
/// the proven parameter `distance` from the certified curve, its floating-point `estimate`, the
/// `slack` it exceeds and, when proven, the branch it strayed `onto`), `unchecked_points`
/// (indices), `looping`, `covered_fraction`, `marched_length` and `certified_length`.
pub fn straying_json(r: &StrayReport) -> Value {
    let points: Vec<Value> = r
        .straying
        .iter()
        .map(|s| {
            let mut v = json!({
                "index": s.index,
                "distance": s.distance,
                "estimate": s.estimate,
                "slack": s.slack,
            });
            if let (Some(j), Value::Object(m)) = (s.onto, &mut v) {
                m.insert("onto".into(), json!(j));
            }
            v
        })
        .collect();
    json!({
        "straying_points": points,
        "unchecked_points": r.unchecked,
        "looping": r.looping,
        "covered_fraction": r.covered_fraction,
        "marched_length": r.marched_length,
        "certified_length": r.certified_length,
    })
}

/// `P([σ],[t]) ∩ Q([u],[v])` for a bounded parameter box; `None` if unbounded or empty.
fn model_box(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
) -> Option<[Interval; 3]> {
    if y.iter()
        .any(|x| x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite())
    {
        return None;
    }
    let (a, b) = (p.enclose(y[0], y[1]), q.enclose(y[2], y[3]));
    let out: [Interval; 3] = std::array::from_fn(|i| a[i].intersection(b[i]));
    (!out.iter().any(|x| x.is_empty())).then_some(out)
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
        "search_complete": s.search_complete,
        "disjoint_pairs": s.disjoint_pairs,
        "loop_free_pairs": s.loop_free_pairs,
        "undecided_regions": s
            .undecided_regions
            .iter()
            .map(|r| json!({"p": r.p, "q": r.q}))
            .collect::<Vec<_>>(),
        "contact_points": s.contact_points,
        "search_seconds": s.search_seconds,
        "march_seconds": s.march_seconds,
    });
    match v {
        Value::Object(m) => m,
        _ => Map::new(),
    }
}
