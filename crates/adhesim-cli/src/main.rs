//! `adhesim`: command-line front end of the adhesim simulator (see `docs/cli.md`).

mod experiment;
mod friction_study;
mod master_plots;
mod output;
mod plots;
mod reference;
mod scenario;
mod summary;
mod sweep;
mod tangential;
mod tangential_plots;

use adhesim::analysis::reference::Hertz;
use adhesim::{AdhesiveParams, AdhesiveSolver, HalfSpace, IndentPulloff, NormalSolver, Profile, ProtocolError};
use anyhow::{anyhow, Context, Result};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// The built-in default scenario (the paper's Fig. 1 case).
const DEFAULT_SCENARIO: &str = include_str!("../../../scenarios/fig1.toml");

/// Adhesive contacts of rough elastic bodies (FFT-accelerated BEM, Popov et al. 2021).
///
/// Without a subcommand, runs the built-in default scenario (the paper's Fig. 1 case)
/// into ./out/default/.
#[derive(Parser)]
#[command(name = "adhesim", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scenario file.
    Run(RunArgs),
    /// Print a closed-form reference curve as CSV to stdout.
    Reference(reference::ReferenceArgs),
    /// Run a parameter study (resumable, parallel, shardable); `sweep merge DIR` rebuilds
    /// its table and plots.
    Sweep(sweep::SweepArgs),
    /// Redraw figures, e.g. `plot master TABLE.csv... [--out DIR]` (master curves).
    Plot(master_plots::PlotArgs),
    /// Rolling / sliding friction study over the Johnson parameter (paper Figs. 7, 8, 10).
    Study(friction_study::StudyArgs),
    /// Analyse a filmed contact experiment (`adhesim experiment SPEC.toml [--out DIR]`), or
    /// generate a synthetic one (`adhesim experiment synth`).
    Experiment(experiment::ExperimentArgs),
}

#[derive(Args)]
struct RunArgs {
    /// Scenario file (TOML).
    scenario: PathBuf,
    /// Output folder [default: out/<scenario file stem>/].
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    options: RunOptions,
}

#[derive(Args, Clone, Default)]
struct RunOptions {
    /// No progress bar and no final report on stdout.
    #[arg(long)]
    quiet: bool,
    /// Worker threads for the FFTs [default: all cores].
    #[arg(long)]
    threads: Option<usize>,
    /// Override a scenario key before validation, e.g. `--set grid.n=64` (repeatable;
    /// VALUE is a TOML value).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => {
            let _ = error.print();
            return if error.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    let result = match cli.command {
        None => run_default(),
        Some(Command::Run(args)) => run_file(&args),
        Some(Command::Reference(args)) => reference::print(&args),
        Some(Command::Sweep(args)) => sweep::command(&args),
        Some(Command::Plot(args)) => master_plots::command(&args),
        Some(Command::Study(args)) => friction_study::run(&args),
        Some(Command::Experiment(args)) => experiment::main(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run_default() -> Result<()> {
    let out = PathBuf::from("out/default");
    let scenario = scenario::load(DEFAULT_SCENARIO, "built-in scenario fig1.toml", Path::new("."), &[])?;
    run(scenario, &out, &RunOptions::default())
}

fn run_file(args: &RunArgs) -> Result<()> {
    let path = &args.scenario;
    let text = std::fs::read_to_string(path).with_context(|| format!("cannot read scenario {}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let scenario = scenario::load(&text, &path.display().to_string(), base, &args.options.set)?;
    let out = match &args.out {
        Some(out) => out.clone(),
        None => {
            let stem = path
                .file_stem()
                .ok_or_else(|| anyhow!("scenario path {} has no file name", path.display()))?;
            Path::new("out").join(stem)
        }
    };
    run(scenario, &out, &args.options)
}

fn run(scenario: scenario::Scenario, out: &Path, options: &RunOptions) -> Result<()> {
    if let Some(threads) = options.threads {
        if threads == 0 {
            return Err(anyhow!("--threads must be >= 1, got 0"));
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("cannot set up the thread pool")?;
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    if scenario.translation.is_some() {
        return tangential::run(scenario, out, options);
    }
    let start = Instant::now();
    let grid = scenario.grid;
    let contact_modulus = scenario.material.contact_modulus();
    let mut operator = HalfSpace::new(grid, scenario.material);
    let mut solver = if scenario.gamma0 > 0.0 {
        NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
            grid,
            contact_modulus,
            scenario.gamma.clone(),
            AdhesiveParams::default(),
        )))
    } else {
        adhesim::protocol::non_adhesive_solver(grid, scenario.material)
    };
    let protocol = IndentPulloff {
        start_depth: scenario.start_depth,
        max_depth: scenario.max_depth,
        depth_step: scenario.depth_step,
        max_retract_steps: scenario.max_retract_steps,
        jump_force_threshold: scenario.jump_force_threshold,
    };
    let o = &scenario.file.output;
    let plan = output::SnapshotPlan {
        chosen: o.snapshot_steps.iter().map(|&s| s as usize).collect(),
        every: o.snapshot_every as usize,
        jump_elements: o.jump_snapshot_elements as usize,
        max_jump_snapshots: o.max_snapshots as usize,
        max_depth_step: scenario.approach_steps.saturating_sub(1),
    };
    let mut observer = output::RunObserver::new(
        out,
        grid,
        scenario.jkr,
        plan,
        2 * scenario.approach_steps,
        options.quiet,
    )?;
    let outcome = protocol.run(&mut operator, &scenario.heights, &mut solver, &mut observer);
    observer.finish()?;
    let protocol_summary = match outcome {
        Ok(summary) => summary,
        Err(ProtocolError::Interrupted(step)) => {
            let cause = observer.error.take().unwrap_or_else(|| anyhow!("interrupted"));
            return Err(cause.context(format!("run stopped at step {step}")));
        }
        Err(error) => {
            return Err(anyhow!(error).context(format!(
                "run failed; {} holds the steps done",
                out.join("curve.csv").display()
            )))
        }
    };
    let hertz = match (scenario.gamma0 > 0.0, scenario.indenter.radius_of_curvature()) {
        (false, Some(radius)) => Some(Hertz {
            radius,
            contact_modulus,
        }),
        _ => None,
    };
    let figures = plots::figures(
        &observer.records,
        &plots::PlotContext {
            jkr: scenario.jkr,
            hertz,
            max_depth: scenario.max_depth,
        },
    );
    let (fits, _) = summary::fit_results(&scenario, &observer.records);
    let overlays = match scenario.jkr {
        Some(jkr) => vec![(
            "force_radius",
            plots::fitted_jkr_overlays(&jkr, &observer.records, fits.gamma_approach, fits.gamma_pulloff),
        )],
        None => Vec::new(),
    };
    let plot_files = plots::write_all_with_overlays(&out.join("plots"), &figures, &overlays)?;
    let wall_seconds = start.elapsed().as_secs_f64();
    let mut warnings = observer.warnings.clone();
    if protocol_summary.touches_border && warnings.is_empty() {
        warnings.push("contact reached the domain border: the domain is too small, enlarge grid.size".into());
    }
    let summary = summary::Summary {
        adhesim_version: env!("CARGO_PKG_VERSION"),
        inputs: &scenario.file,
        derived: &scenario.derived,
        results: summary::Results {
            fits,
            ..summary::Results::from_protocol(&protocol_summary)
        },
        performance: summary::Performance::new(
            wall_seconds,
            protocol_summary.cg_iterations,
            protocol_summary.operator_applications,
            protocol_summary.solves,
            protocol_summary.steps,
            &observer,
        ),
        warnings,
    };
    summary::write(&out.join("summary.json"), &summary)?;
    if !options.quiet {
        println!("adhesim: {} steps in {:.1} s", protocol_summary.steps, wall_seconds);
        if let Some(jkr) = scenario.jkr {
            println!(
                "  max adhesive force = {:.4} |F_JKR|, jumps = {}",
                protocol_summary.max_adhesive_force / jkr.critical_force().abs(),
                protocol_summary.jumps
            );
        }
        println!("outputs in {}/", out.display());
        println!("  summary.json, curve.csv");
        println!("  {}", plot_files.join(", "));
        println!(
            "  snapshots/: {} contact maps (largest_contact.png, max_depth.png, pull_off.png, jump_*.png, step_*.png)",
            observer.snapshot_files.len()
        );
    }
    Ok(())
}
