//! The `ssitrace` command line: `ssitrace trace SCENE.json ...` and `ssitrace demo`.

use clap::{Parser, Subcommand, ValueEnum};
use inari::Interval;
use ssitrace::certify::contact::{CertifiedContact, ContactEnd, StepCase};
use ssitrace::certify::CertifiedEnd;
use ssitrace::check::straying::StrayReport;
use ssitrace::io::intersection_json::mark_pair;
use ssitrace::io::result_json::write_result;
use ssitrace::io::scene::{Method, Scene, ShellScene};
use ssitrace::march::branch::{BranchStatus, Event, EventKind};
use ssitrace::pipeline::{RunOptions, RunReport, ShellRunReport};
use ssitrace::{BranchCertificate, Engine};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// The built-in demo: Wu & Andrade's Fig. 7, a degree-6 surface against a plane (three loops),
/// marched and certified.
const DEMO_SCENE: &str = include_str!("../scenes/wu_andrade_fig7.json");

#[derive(Parser)]
#[command(
    name = "ssitrace",
    version,
    about = "Surface/surface intersection curves of rational Bézier patches"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    /// Floating-point circular-step marching.
    March,
    /// March to find the branches, then certify each (slow; within the step budget).
    Validated,
    /// Like `validated`, and report the marched and certified results side by side.
    Both,
}

#[derive(Clone, Copy, ValueEnum)]
enum EngineArg {
    /// Krawczyk-proven tubes around septic predictors between the marched points (fast).
    Chain,
    /// The validated Taylor ODE solver by arc length (proven arc lengths; slow).
    Taylor,
}

#[derive(clap::Args)]
struct Outputs {
    /// Write the result JSON here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write an SVG picture here.
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Write the certified curves as B-rep edges here (JSON: 3D B-spline, p-curves, proven
    /// edge tolerance; docs/result-format.md).
    #[arg(long, value_name = "FILE")]
    edges: Option<PathBuf>,
    /// Write the certified curves as a STEP file here (B_SPLINE_CURVE_WITH_KNOTS; p-curves with
    /// --step-pcurves; docs/step.md).
    #[arg(long, value_name = "FILE")]
    step_out: Option<PathBuf>,
    /// With --step-out: write each part of a curve (a stretch on one pair of Bézier pieces) as a
    /// SURFACE_CURVE with its two p-curves, on the pieces written as B-spline surfaces.
    #[arg(long)]
    step_pcurves: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Trace the intersection of the two surfaces of a scene file, or of the faces of two STEP
    /// files.
    Trace {
        /// The scene file (JSON; format in the README), or the first STEP file (`.step`/`.stp`).
        scene: PathBuf,
        /// The second STEP file, when the first argument is a STEP file: every face of the first
        /// is intersected with every face of the second.
        second: Option<PathBuf>,
        /// Tracing method (default: the scene's, else `both`).
        #[arg(long, value_enum)]
        method: Option<MethodArg>,
        /// Certification engine of transversal branches (default `chain`).
        #[arg(long, value_enum)]
        engine: Option<EngineArg>,
        /// Marching step L (default: the scene's, else 0.05), in model units for parts up to 50 units
        /// across and scaled with larger ones.
        #[arg(long)]
        step: Option<f64>,
        /// Model-space tolerance a certified branch should meet (default: the scene's, else 1e-9).
        #[arg(long)]
        tolerance: Option<f64>,
        /// Certified step budget per half branch (default 20000).
        #[arg(long)]
        max_steps: Option<usize>,
        /// Write the certified tube pieces into the result JSON (large).
        #[arg(long)]
        tubes: bool,
        /// Wall-clock limit of the certification in seconds: when it expires, every branch
        /// still being certified ends unproven ("time limit"), with what is proven so far.
        #[arg(long, value_name = "SECONDS")]
        time_limit: Option<f64>,
        #[command(flatten)]
        outputs: Outputs,
    },
    /// Run the built-in example (three nested loops), march and certify it, and print a summary.
    Demo {
        #[command(flatten)]
        outputs: Outputs,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> ssitrace::Result<()> {
    let (scene, opts, outputs) = match cli.command {
        Command::Trace {
            scene,
            second,
            method,
            engine,
            step,
            tolerance,
            max_steps,
            tubes,
            time_limit,
            outputs,
        } => {
            let step_scene = match (ssitrace::pipeline::is_step_path(&scene), &second) {
                (true, Some(b)) => Some(ssitrace::pipeline::read_step_scene(&scene, b)?),
                (true, None) => return Err(usage("a STEP file needs a second STEP file")),
                (false, Some(_)) => {
                    return Err(usage("a second file is only taken after a STEP file"))
                }
                (false, None) => None,
            };
            let s = match &step_scene {
                Some(st) => st.scene.clone(),
                None => ShellScene::from_path(&scene)?,
            };
            let mut o = RunOptions::from_scene_options(&s.options);
            if let Some(m) = method {
                o.method = match m {
                    MethodArg::March => Method::March,
                    MethodArg::Validated => Method::Validated,
                    MethodArg::Both => Method::Both,
                };
            }
            if let Some(e) = engine {
                o.engine = match e {
                    EngineArg::Chain => Engine::Chain,
                    EngineArg::Taylor => Engine::Taylor,
                };
            }
            if let Some(l) = step {
                o.step = l;
            }
            if let Some(t) = tolerance {
                o.required_tolerance = t;
            }
            if let Some(n) = max_steps {
                o.max_steps = n;
            }
            o.tubes = tubes;
            if let Some(t) = time_limit {
                let limit = std::time::Duration::try_from_secs_f64(t).map_err(|_| {
                    ssitrace::Error::input(
                        "--time-limit",
                        ssitrace::InputProblem::WrongShape(format!(
                            "{t} is not a number of seconds ≥ 0"
                        )),
                    )
                })?;
                o.time_limit = Some(limit);
            }
            if let Some(st) = &step_scene {
                return run_shells(&s, &o, &outputs, Some(st));
            }
            match s.as_pair() {
                Some(pair) => (pair, o, outputs),
                None => return run_shells(&s, &o, &outputs, None),
            }
        }
        Command::Demo { outputs } => {
            // The scene marches only when traced by hand; the demo certifies it.
            let s = Scene::from_json_str(DEMO_SCENE)?;
            let mut o = RunOptions::from_scene(&s);
            o.method = Method::Both;
            (s, o, outputs)
        }
    };
    let started = Instant::now();
    // The result document's metadata is built only when it is written.
    let mut report = if outputs.out.is_some() {
        ssitrace::pipeline::run(&scene, &opts)?
    } else {
        ssitrace::pipeline::run_without_meta(&scene, &opts)?
    };
    let elapsed = started.elapsed().as_secs_f64();
    say(&summary(&scene, &report, &opts, elapsed));
    mark_pair(&mut report.meta, &report.result, [0, 0]);
    if let Some(path) = &outputs.out {
        write_result(path, &report.result.marched(), &report.meta)?;
        say(&format!("result written to {}\n", path.display()));
    }
    if let Some(path) = &outputs.svg {
        write_svg(path, &scene, &report)?;
        say(&format!("picture written to {}\n", path.display()));
    }
    if outputs.edges.is_some() || outputs.step_out.is_some() {
        let [p, q] = &scene.surfaces;
        let edges = ssitrace::edge::edges_of(p, q, &report.result);
        let name = scene.options.name.as_deref();
        if let Some(path) = &outputs.edges {
            write_edges_file(path, name, "branch", &edges)?;
        }
        if let Some(path) = &outputs.step_out {
            let faces = [
                vec![ssitrace::shell::Face::from_patch(p.clone())],
                vec![ssitrace::shell::Face::from_patch(q.clone())],
            ];
            let pieces = outputs.step_pcurves.then_some(&faces);
            write_step_file(path, name, &edges, None, pieces)?;
        }
    }
    Ok(())
}

/// An error of the command line's use.
fn usage(message: &str) -> ssitrace::Error {
    ssitrace::Error::input(
        "command line",
        ssitrace::InputProblem::WrongShape(message.into()),
    )
}

/// Writes the certified edges as STEP curves and says how many.
fn write_step_file(
    path: &std::path::Path,
    name: Option<&str>,
    edges: &[(
        usize,
        Result<ssitrace::edge::Edge, ssitrace::edge::EdgeError>,
    )],
    length_unit: Option<&str>,
    pieces: Option<&[Vec<ssitrace::shell::Face>; 2]>,
) -> ssitrace::Result<()> {
    let (text, n) = ssitrace::pipeline::step_curves_text(
        name.unwrap_or("ssitrace"),
        edges,
        length_unit,
        pieces,
    )?;
    std::fs::write(path, text).map_err(|e| ssitrace::Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    say(&format!(
        "{n} certified curve(s) or part(s) of {} curve(s) written to {} (STEP, {})\n",
        edges.len(),
        path.display(),
        if pieces.is_some() {
            "with p-curves"
        } else {
            "without p-curves"
        }
    ));
    Ok(())
}

/// Writes the edge document and says how many edges it holds.
fn write_edges_file(
    path: &std::path::Path,
    name: Option<&str>,
    source: &str,
    edges: &[(
        usize,
        Result<ssitrace::edge::Edge, ssitrace::edge::EdgeError>,
    )],
) -> ssitrace::Result<()> {
    let doc = ssitrace::io::edge_json::edges_document(name, source, edges);
    ssitrace::io::edge_json::write_edges(path, &doc)?;
    let made = edges.iter().filter(|(_, e)| e.is_ok()).count();
    say(&format!(
        "{made} edge(s) of {} written to {}\n",
        edges.len(),
        path.display()
    ));
    for (k, e) in edges {
        match e {
            Ok(e) => say(&format!(
                "  {source} {k}: {} control points, edge tolerance {:.2e}{}{}\n",
                e.curve.points.len(),
                e.edge_tolerance,
                if e.closed { ", closed" } else { "" },
                match (e.shortfall, e.requested) {
                    (Some(s), Some(r)) => format!(" (above the requested {r:.1e}: {s})"),
                    _ => String::new(),
                }
            )),
            Err(err) => say(&format!("  {source} {k}: no edge ({err})\n")),
        }
    }
    Ok(())
}

/// A scene of shells (several faces, or NURBS surfaces of several knot spans): every piece
/// pair traced, a summary printed, the merged result written.
fn run_shells(
    scene: &ShellScene,
    opts: &RunOptions,
    outputs: &Outputs,
    step: Option<&ssitrace::pipeline::StepScene>,
) -> ssitrace::Result<()> {
    let started = Instant::now();
    let mut report = ssitrace::pipeline::run_shells(scene, opts)?;
    let elapsed = started.elapsed().as_secs_f64();
    if let Some(st) = step {
        ssitrace::pipeline::mark_step(&mut report.meta, st);
        say(&step_summary(st));
    }
    say(&shell_summary(scene, &report, opts, elapsed));
    if let Some(path) = &outputs.out {
        write_result(path, &report.curves, &report.meta)?;
        say(&format!("result written to {}\n", path.display()));
    }
    if let Some(path) = &outputs.svg {
        say(&format!(
            "no picture written to {}: pictures of shell scenes are not drawn yet\n",
            path.display()
        ));
    }
    if outputs.edges.is_some() || outputs.step_out.is_some() {
        let [a, b] = &scene.shells;
        let edges = ssitrace::edge::edges_of_shells(a, b, &report.result);
        let name = scene.options.name.as_deref();
        if let Some(path) = &outputs.edges {
            write_edges_file(path, name, "curve", &edges)?;
        }
        if let Some(path) = &outputs.step_out {
            let unit = step.and_then(|s| s.models[0].length_unit.as_deref());
            let pieces = outputs.step_pcurves.then_some(&scene.shells);
            write_step_file(path, name, &edges, unit, pieces)?;
        }
    }
    Ok(())
}

/// What was read from two STEP files: faces, surface kinds, trimmed faces, read time.
fn step_summary(step: &ssitrace::pipeline::StepScene) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    for (file, m) in step.files.iter().zip(&step.models) {
        let trimmed = m.faces.iter().filter(|f| f.trimmed).count();
        let kinds: Vec<String> = m
            .faces
            .iter()
            .map(|f| format!("#{} {}", f.entity, f.surface_kind))
            .collect();
        let _ = writeln!(
            out,
            "{file}: {} face(s) ({}), {trimmed} trimmed (traced on their whole surface patch)",
            m.faces.len(),
            kinds.join(", ")
        );
    }
    let _ = writeln!(out, "STEP read in {:.2} ms", step.read_seconds * 1e3);
    out
}

/// The summary of a shell run: counts, then each traced piece pair and its branches.
fn shell_summary(
    scene: &ShellScene,
    report: &ShellRunReport,
    opts: &RunOptions,
    seconds: f64,
) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let name = scene.options.name.as_deref().unwrap_or("scene");
    let r = &report.result;
    let _ = writeln!(
        out,
        "{name}: {} x {} face(s), {} piece pair(s), {} skipped by their bounding boxes, {} branch(es), {:.1} ms",
        scene.shells[0].len(),
        scene.shells[1].len(),
        r.piece_pairs,
        r.skipped_pairs,
        r.branch_count(),
        seconds * 1e3
    );
    if r.edge_copies > 0 {
        let _ = writeln!(
            out,
            "  {} branch(es) along a shared edge (knot line, seam or face edge) traced by both pieces: one copy kept",
            r.edge_copies
        );
    }
    if r.pole_settled > 0 {
        let _ = writeln!(
            out,
            "  {} undecided search region(s) at a pole settled by the proven join through it",
            r.pole_settled
        );
    }
    // Branches a proven corner join covers (shell-wide numbers, as the joins number them).
    let absorbed: std::collections::HashSet<usize> = r
        .curves
        .iter()
        .flat_map(|c| &c.joins)
        .filter_map(|j| j.corner.as_ref())
        .flat_map(|c| c.absorbed.iter().copied())
        .collect();
    let mut g = 0;
    for p in &r.pairs {
        if p.result.branches.is_empty() && p.result.is_complete() {
            continue;
        }
        let _ = writeln!(
            out,
            "  faces {:?}, pieces {:?}: {} branch(es){}",
            p.faces,
            p.pieces,
            p.result.branches.len(),
            if p.result.is_complete() {
                ""
            } else {
                " (warning: search not complete)"
            }
        );
        for traced in &p.result.branches {
            let b = &traced.marched;
            let _ = writeln!(
                out,
                "    branch {g}: {} to {}, {} points",
                b.ends[0],
                b.ends[1],
                b.points.len()
            );
            if absorbed.contains(&g) {
                let _ = writeln!(
                    out,
                    "      a sliver of a curve at a corner of pieces, a vertex of faces or a pole, covered by a proven join"
                );
            } else if let Some(c) = &traced.certificate {
                let _ = writeln!(out, "  {}", certificate_line(c, opts.required_tolerance));
            }
            g += 1;
        }
    }
    for (k, c) in r.curves.iter().enumerate() {
        let proven = c.joins.iter().filter(|j| j.status.is_proven()).count();
        use ssitrace::shell::edges::EdgeKind;
        let count = |kind: EdgeKind| c.joins.iter().filter(|j| j.edge == kind).count();
        let corners = c
            .joins
            .iter()
            .filter(|j| {
                j.corner.is_some() && !matches!(j.edge, EdgeKind::Pole | EdgeKind::NearEdge)
            })
            .count();
        let mut poles = String::new();
        for (kind, what) in [
            (EdgeKind::Pole, "through a pole"),
            (
                EdgeKind::NearEdge,
                "across edges shared to within the tolerance",
            ),
        ] {
            let n = count(kind);
            if n > 0 {
                poles += &format!(", {n} {what}");
            }
        }
        let tolerance = c
            .certified_tolerance
            .map_or("not certified as a whole".to_string(), |t| {
                format!("certified tolerance {t:.3e}")
            });
        let _ = writeln!(
            out,
            "  curve {k}: {}, {} part(s), {tolerance}; joins: {proven} of {} proven ({corners} across corners{poles})",
            if c.closed { "closed" } else { "open" },
            c.parts.len(),
            c.joins.len(),
        );
    }
    out
}

/// Draws the marched curves with the certified boxes and contacts over them.
#[cfg(feature = "svg")]
fn write_svg(path: &std::path::Path, scene: &Scene, report: &RunReport) -> ssitrace::Result<()> {
    use ssitrace::io::svg::{
        add_contact_boxes, certified_overlay, write_svg_with_overlay, DEFAULT_OVERLAY_BOXES,
    };
    let title = scene
        .options
        .name
        .clone()
        .unwrap_or_else(|| "ssitrace".into());
    let domains = [scene.surfaces[0].domain(), scene.surfaces[1].domain()];
    let r = &report.result;
    let certified: Vec<_> = r.branches.iter().filter_map(|b| b.certified()).collect();
    let mut overlay = certified_overlay(&certified, DEFAULT_OVERLAY_BOXES);
    add_contact_boxes(&mut overlay, &r.contacts, DEFAULT_OVERLAY_BOXES);
    write_svg_with_overlay(path, &r.marched(), domains, &title, &overlay)
}

/// Without the `svg` feature there is no picture.
#[cfg(not(feature = "svg"))]
fn write_svg(path: &std::path::Path, _: &Scene, _: &RunReport) -> ssitrace::Result<()> {
    Err(ssitrace::Error::Render(format!(
        "{}: this ssitrace was built without the `svg` feature",
        path.display()
    )))
}

/// Prints to standard output, ignoring a closed pipe (e.g. `ssitrace demo | head -1`).
fn say(text: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

/// One summary line for a branch's certification.
fn certificate_line(c: &BranchCertificate, tolerance: f64) -> String {
    let ms = c.seconds * 1e3;
    match &c.result {
        Ok(b) => {
            // As the JSON's `max_width`: the start box and every step's tight end box.
            let max_width = b
                .widths
                .iter()
                .copied()
                .chain(b.start.iter().map(|x| x.wid()))
                .fold(0.0, f64::max);
            let meets = if b.certified_tolerance <= tolerance {
                "meets"
            } else {
                "does NOT meet"
            };
            let line = format!(
                "    certified: {} steps, tolerance {:.3e} ({meets} {:.1e}), ends {} / {}, max width {:.3e}, {:.1} ms",
                b.steps(),
                b.certified_tolerance,
                tolerance,
                b.ends[0],
                b.ends[1],
                max_width,
                ms
            );
            match &b.tolerance_limit {
                Some(l) if b.certified_tolerance > tolerance => {
                    let at = l.near.map(|x| format!("{:.6}", x.mid()));
                    format!(
                        "{line}\n    why: {} (near σ, t, u, v = {})",
                        l.reason,
                        at.join(", ")
                    )
                }
                _ => line,
            }
        }
        Err(e) => format!("    certification FAILED ({ms:.1} ms): {e}"),
    }
}

/// One summary line for a branch's straying check, `warning:` first when a point strays or the
/// marcher looped.
fn straying_line(r: &StrayReport) -> String {
    let checked = format!(
        "covers {:.1}% of the certified arc, {} unchecked point(s)",
        100.0 * r.covered_fraction,
        r.unchecked.len()
    );
    if !r.has_problems() {
        return format!("    marched points: none strays, {checked}");
    }
    let mut what = Vec::new();
    if !r.straying.is_empty() {
        let worst = r.straying.iter().map(|s| s.distance).fold(0.0, f64::max);
        let onto: Vec<String> = r
            .straying
            .iter()
            .filter_map(|s| s.onto)
            .fold(Vec::new(), |mut v, j| {
                if !v.contains(&j) {
                    v.push(j);
                }
                v
            })
            .iter()
            .map(|j| format!("onto branch {j}"))
            .collect();
        let first: Vec<String> = r
            .straying
            .iter()
            .take(5)
            .map(|s| s.index.to_string())
            .collect();
        what.push(format!(
            "{} point(s) stray (indices {}{}, proven distance up to {worst:.2e}{}{})",
            r.straying.len(),
            first.join(", "),
            if r.straying.len() > 5 { ", ..." } else { "" },
            if onto.is_empty() { "" } else { ", " },
            onto.join(", ")
        ));
    }
    if r.looping {
        what.push(format!(
            "the march goes round the loop more than once ({:.4} marched vs {:.4} certified)",
            r.marched_length, r.certified_length
        ));
    }
    format!("    warning: {}; {checked}", what.join("; "))
}

/// Whether the model point `xyz` lies in one of a certified contact's boxes (a step's a-priori
/// box or a box of its cover), grown by 1e-6 for the marcher's own accuracy (a display rule for
/// the summary, not a proof).
fn contact_holds(c: &CertifiedContact, xyz: &[f64; 3]) -> bool {
    let grow = 1e-6 * (1.0 + xyz.iter().map(|v| v.abs()).fold(0.0, f64::max));
    let inside = |b: &[Interval; 3]| {
        (0..3).all(|i| b[i].inf() - grow <= xyz[i] && xyz[i] <= b[i].sup() + grow)
    };
    c.steps.iter().any(|s| inside(&s.xyz)) || c.cover.boxes.iter().any(|b| inside(&b.xyz))
}

fn contact_end_name(e: &ContactEnd) -> String {
    match e {
        ContactEnd::Boundary { surface } => {
            format!("boundary of {}", if *surface == 0 { "P" } else { "Q" })
        }
        ContactEnd::CaseChanged { case, .. } => format!("case changed ({case:?})"),
        ContactEnd::StepFailed { .. } => "step failed".into(),
        ContactEnd::Budget { .. } => "budget spent".into(),
        ContactEnd::NotTraced => "not traced".into(),
    }
}

fn contact_line(k: usize, c: &CertifiedContact, folded: usize) -> String {
    let cover = format!(
        "cover {} box(es){}",
        c.cover.boxes.len(),
        if c.cover.resolved {
            ""
        } else {
            " (not resolved)"
        }
    );
    // Nothing traced from a start proven a crossing or an isolated contact: a point, not a
    // curve (the crossing of two branches at a node is the march's and the search's).
    let point = match c.start_case {
        _ if !c.steps.is_empty() => None,
        StepCase::BranchPoint => Some("crossing of two branches (a node: Δ > 0 proven on its box)"),
        StepCase::IsolatedPoint => Some("isolated contact point (Δ < 0 proven on its box)"),
        _ => None,
    };
    if let Some(what) = point {
        return format!("  contact {k}: {what}, {cover}; {folded} singular event(s) there");
    }
    format!(
        "  contact {k}: tangential contact curve (the tangential field's solution from the \
         event; touching is not provable), certified in {} steps, tube radius {:.3e}, \
         ends {} / {}, {cover}; {folded} singular event(s) on it",
        c.steps.len(),
        c.tube_radius,
        contact_end_name(&c.ends[0]),
        contact_end_name(&c.ends[1]),
    )
}

fn summary(scene: &Scene, report: &RunReport, opts: &RunOptions, seconds: f64) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let name = scene.options.name.as_deref().unwrap_or("scene");
    let r = &report.result;
    let _ = writeln!(
        out,
        "{name}: {} branch(es), {} event(s), {:.1} ms",
        r.branches.len(),
        r.events.len(),
        seconds * 1e3
    );
    for traced in &r.branches {
        let b = &traced.marched;
        let status = match b.status {
            BranchStatus::Closed => "closed loop",
            BranchStatus::Open => "open",
            BranchStatus::Incomplete => "INCOMPLETE",
        };
        let desc = if b.status == BranchStatus::Closed {
            String::new()
        } else {
            format!(" from {} to {}", b.ends[0], b.ends[1])
        };
        let _ = writeln!(
            out,
            "  branch {}: {status}{desc}, {} points",
            b.id,
            b.points.len()
        );
        if let Some(c) = &traced.certificate {
            let _ = writeln!(out, "{}", certificate_line(c, opts.required_tolerance));
            let closed = |e: &CertifiedEnd| *e == CertifiedEnd::ClosedLoop;
            match (&b.status, &c.result) {
                (BranchStatus::Closed, Ok(cb)) if !cb.ends.iter().all(closed) => {
                    let _ = writeln!(
                        out,
                        "    warning: the marched loop's closure is NOT proven (the certificate \
                         ends {} / {})",
                        cb.ends[0], cb.ends[1]
                    );
                }
                (BranchStatus::Closed, Err(_)) => {
                    let _ = writeln!(
                        out,
                        "    warning: the marched loop's closure is NOT proven (no certificate)"
                    );
                }
                _ => {}
            }
        }
        if let Some(s) = &traced.straying {
            let _ = writeln!(out, "{}", straying_line(s));
        }
    }
    // A certified contact curve is one line; the marcher's events on it are folded into it.
    let on_contact = |e: &Event| {
        (e.kind == EventKind::Singular)
            .then(|| r.contacts.iter().position(|c| contact_holds(c, &e.xyz)))
            .flatten()
    };
    for (k, c) in r.contacts.iter().enumerate() {
        let folded = r.events.iter().filter(|e| on_contact(e) == Some(k)).count();
        let _ = writeln!(out, "{}", contact_line(k, c, folded));
    }
    for e in r.events.iter().filter(|e| on_contact(e).is_none()) {
        let _ = writeln!(
            out,
            "  event {:?} at xyz = ({:.6}, {:.6}, {:.6})",
            e.kind, e.xyz[0], e.xyz[1], e.xyz[2]
        );
    }
    if let Some(c) = &r.stats.certify {
        let march = r.stats.march_seconds;
        let _ = writeln!(
            out,
            "  time: marching {:.1} ms, certified {:.1} ms ({:.1} ms wall), ratio certified/marching {:.1}",
            march * 1e3,
            c.seconds * 1e3,
            c.wall_seconds * 1e3,
            c.seconds / march.max(1e-9)
        );
    }
    let s = &r.stats.search;
    if r.is_complete() {
        let _ = writeln!(
            out,
            "  search complete: {} pair(s) proven disjoint, {} proven free of closed loops{}",
            s.disjoint_pairs,
            s.loop_free_pairs,
            match s.node_regions {
                0 => String::new(),
                n => format!(", {n} neighbourhood(s) of singular points settled"),
            }
        );
    } else {
        let _ = writeln!(out,
            "  warning: search not complete: {} undecided region(s){}, {} undecided boundary leaves, {} failed start(s): small features may be missing (regions in the result's stats)",
            s.undecided_regions.len(),
            if s.search_truncated { ", search truncated" } else { "" },
            s.undecided_leaves,
            s.failed_starts
        );
    }
    out
}
