//! The `ssitrace` command line: `ssitrace trace SCENE.json ...` and `ssitrace demo`.

use clap::{Parser, Subcommand, ValueEnum};
use ssitrace::intersection::{BranchStatus, EndReason};
use ssitrace::io::result_json::write_result;
use ssitrace::io::scene::{Method, Scene};
use ssitrace::io::svg::write_svg;
use ssitrace::marching::intersect::IntersectOutcome;
use ssitrace::pipeline::{run_scene, RunOptions};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// The built-in demo: Wu & Andrade's Fig. 7, a degree-6 surface against a plane (three loops).
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
    /// Certified tracing (not available yet).
    Validated,
    /// Both (not available yet).
    Both,
}

#[derive(clap::Args)]
struct Outputs {
    /// Write the result JSON here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write an SVG picture here.
    #[arg(long)]
    svg: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Command {
    /// Trace the intersection of the two surfaces of a scene file.
    Trace {
        /// The scene file (JSON; format in the README).
        scene: PathBuf,
        /// Tracing method (default: the scene's, else `march`).
        #[arg(long, value_enum)]
        method: Option<MethodArg>,
        /// Marching step L (default: the scene's, else 0.05).
        #[arg(long)]
        step: Option<f64>,
        #[command(flatten)]
        outputs: Outputs,
    },
    /// Run the built-in example (three nested loops) and print a summary.
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
            method,
            step,
            outputs,
        } => {
            let s = Scene::from_path(&scene)?;
            let mut o = RunOptions::from_scene(&s);
            if let Some(m) = method {
                o.method = match m {
                    MethodArg::March => Method::March,
                    MethodArg::Validated => Method::Validated,
                    MethodArg::Both => Method::Both,
                };
            }
            if let Some(l) = step {
                o.step = l;
            }
            (s, o, outputs)
        }
        Command::Demo { outputs } => {
            let s = Scene::from_json_str(DEMO_SCENE)?;
            let o = RunOptions::from_scene(&s);
            (s, o, outputs)
        }
    };
    let started = Instant::now();
    let (outcome, meta) = run_scene(&scene, &opts)?;
    let elapsed = started.elapsed().as_secs_f64();
    say(&summary(&scene, &outcome, elapsed));
    if let Some(path) = &outputs.out {
        write_result(path, &outcome.intersection, &meta)?;
        say(&format!("result written to {}\n", path.display()));
    }
    if let Some(path) = &outputs.svg {
        let title = scene
            .options
            .name
            .clone()
            .unwrap_or_else(|| "ssitrace".into());
        let domains = [scene.surfaces[0].domain(), scene.surfaces[1].domain()];
        write_svg(path, &outcome.intersection, domains, &title)?;
        say(&format!("picture written to {}\n", path.display()));
    }
    Ok(())
}

/// Prints to standard output, ignoring a closed pipe (e.g. `ssitrace demo | head -1`).
fn say(text: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

fn end_name(e: &EndReason) -> String {
    match e {
        EndReason::Boundary { surface } => format!("boundary of {}", ["P", "Q"][(*surface).min(1)]),
        EndReason::ClosedLoop => "closed".into(),
        EndReason::Singular => "singular point".into(),
        EndReason::NewtonFailed => "Newton failed".into(),
        EndReason::PointLimit => "point limit".into(),
    }
}

fn summary(scene: &Scene, outcome: &IntersectOutcome, seconds: f64) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let name = scene.options.name.as_deref().unwrap_or("scene");
    let ix = &outcome.intersection;
    let _ = writeln!(
        out,
        "{name}: {} branch(es), {} event(s), {:.1} ms",
        ix.branches.len(),
        ix.events.len(),
        seconds * 1e3
    );
    for b in &ix.branches {
        let status = match b.status {
            BranchStatus::Closed => "closed loop",
            BranchStatus::Open => "open",
            BranchStatus::Incomplete => "INCOMPLETE",
        };
        let desc = if b.status == BranchStatus::Closed {
            String::new()
        } else {
            format!(" from {} to {}", end_name(&b.ends[0]), end_name(&b.ends[1]))
        };
        let _ = writeln!(
            out,
            "  branch {}: {status}{desc}, {} points",
            b.id,
            b.points.len()
        );
    }
    for e in &ix.events {
        let _ = writeln!(
            out,
            "  event {:?} at xyz = ({:.6}, {:.6}, {:.6})",
            e.kind, e.xyz[0], e.xyz[1], e.xyz[2]
        );
    }
    let s = &outcome.stats;
    if s.undecided_leaves > 0 || s.search_truncated || s.failed_starts > 0 {
        let _ = writeln!(out,
            "  warning: {} undecided search box(es){}, {} failed start(s): small features may be missing",
            s.undecided_leaves,
            if s.search_truncated { ", search truncated" } else { "" },
            s.failed_starts
        );
    }
    out
}
