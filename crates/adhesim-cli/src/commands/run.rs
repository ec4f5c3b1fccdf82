//! `adhesim run` (and `adhesim` without a subcommand): one scenario through the scenario
//! crate's run into a folder (`adhesim_scenario::output::run`), with the command line's
//! pictures and progress bar (`crate::output`), then the report on stdout.

use crate::{output, resources};
use adhesim::{ProtocolSummary, RunSummary, ShearSummary, TranslationSummary};
use adhesim_figures::run_figures::RunFigures;
use adhesim_scenario::output::checkpoint::CheckpointPolicy;
use adhesim_scenario::output::folder;
use adhesim_scenario::output::observer::RunProgress;
use adhesim_scenario::output::run::{run_case, FolderRunOptions};
use adhesim_scenario::{ProtocolSetup, RunOutcome, RunResults, ValidScenario};
use anyhow::{Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};

/// The built-in default scenario (the paper's Fig. 1 case).
const DEFAULT_SCENARIO: &str = include_str!("../../../../scenarios/fig1.toml");

#[derive(Args)]
pub struct RunArgs {
    /// Scenario file (TOML).
    scenario: PathBuf,
    /// Output folder [default: out/<scenario file stem>/].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write into --out even when it is a non-empty folder that is not an adhesim run
    /// folder (its curve.csv, summary.json, plots/ and snapshots/ are replaced).
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    options: RunOptions,
}

#[derive(Args, Clone, Default)]
pub struct RunOptions {
    /// No progress bar and no final report on stdout.
    #[arg(long)]
    pub quiet: bool,
    /// Worker threads for the FFTs [default: all cores].
    #[arg(long)]
    pub threads: Option<usize>,
    /// Run even when the memory estimate of the grid exceeds the memory available
    /// (`MemAvailable` of /proc/meminfo), e.g. where swap or a lazy allocator makes it fit
    /// (not beyond the address-space limit of `ulimit -v`, which nothing gets past).
    #[arg(long)]
    pub allow_large: bool,
    /// Override a scenario key before validation, e.g. `--set grid.n=64` (repeatable;
    /// VALUE is a TOML value).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Also write the snapshot fields as NetCDF-3 (`fields.nc`) besides `fields.npz`.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub fields: Option<FieldsFormat>,
    /// Mid-run checkpoints into the folder (a sweep case; not an option of `adhesim run`).
    #[arg(skip)]
    pub checkpoint: Option<CheckpointPolicy>,
}

/// Extra formats of the snapshot fields (`fields.npz` is always written).
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldsFormat {
    /// `fields.nc`, NetCDF classic, for xarray.
    Netcdf,
}

/// `adhesim` without a subcommand: the built-in scenario into ./out/default/.
pub fn run_default() -> Result<()> {
    let out = PathBuf::from("out/default");
    let scenario = adhesim_scenario::load_within(
        DEFAULT_SCENARIO,
        "built-in scenario fig1.toml",
        Path::new("."),
        &[],
        resources::memory_limit(false)?.as_ref(),
    )?;
    folder::prepare_run_folder(&out, false).context(
        "`adhesim` without a subcommand writes into out/default; `adhesim run SCENARIO --out DIR` chooses the folder",
    )?;
    run(&scenario, &out, &RunOptions::default())
}

/// `adhesim run SCENARIO`.
pub fn command(args: &RunArgs) -> Result<()> {
    let path = &args.scenario;
    let text = adhesim_scenario::read_input_text(path, "scenario")?;
    let base = path.parent().unwrap_or(Path::new("."));
    let scenario = adhesim_scenario::load_within(
        &text,
        &path.display().to_string(),
        base,
        &args.options.set,
        resources::memory_limit(args.options.allow_large)?.as_ref(),
    )
    .map_err(|e| {
        let resources = e.kind == adhesim_scenario::ErrorKind::Resources;
        let error = anyhow::Error::new(e);
        if resources && args.options.allow_large {
            error.context("refused before allocating, even with --allow-large")
        } else if resources {
            error.context("refused before allocating (pass --allow-large to run anyway)")
        } else {
            error
        }
    })?;
    // The thread count is checked (and clamped) before anything is written.
    let threads = args.options.threads.map(resources::clamp_threads).transpose()?;
    let out = folder::output_dir(args.out.as_deref(), path, "scenario")?;
    folder::prepare_run_folder(&out, args.force)?;
    let options = RunOptions {
        threads,
        ..args.options.clone()
    };
    run(&scenario, &out, &options)
}

/// Runs a validated scenario into `out` through the scenario crate's pipeline
/// ([`run_case`]) with the figures crate's pictures and the command line's progress bar: curve.csv,
/// snapshots, plots, summary.json. `out` is new, or made ready by
/// [`folder::prepare_run_folder`]; it gets the run marker.
pub fn run(scenario: &ValidScenario, out: &Path, options: &RunOptions) -> Result<()> {
    let mut progress = output::TerminalProgress::new(scenario.expected_steps(), options.quiet, scenario.jkr);
    run_with_progress(scenario, out, options, &mut progress)
}

/// [`run`] with the progress shown by `progress` (a sweep case's share of the sweep's bar).
/// `options.threads` is a count [`resources::clamp_threads`] has checked (`command` checks
/// it before the folder is made).
pub fn run_with_progress(
    scenario: &ValidScenario,
    out: &Path,
    options: &RunOptions,
    progress: &mut (dyn RunProgress + Send),
) -> Result<()> {
    let folder_options = FolderRunOptions {
        pictures: Some(&RunFigures),
        netcdf: options.fields == Some(FieldsFormat::Netcdf),
        checkpoint: options.checkpoint.as_ref(),
    };
    // `--threads N`: a pool of the run's own, not rayon's global one (which a process can
    // size once: a second run in the same process, as the Python package's console entry
    // makes, was refused).
    let done = match options.threads {
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .context("cannot set up the thread pool")?
            .install(|| run_case(scenario, out, folder_options, progress))?,
        None => run_case(scenario, out, folder_options, progress)?,
    };
    let outcome = &done.outcome;
    if !options.quiet {
        let wall_seconds = done.wall_seconds;
        match &outcome.report {
            RunSummary::Indentation(summary) => print_indentation(scenario, summary, wall_seconds),
            RunSummary::Translation(summary) => print_translation(scenario, summary, outcome, wall_seconds),
            RunSummary::Shear(summary) => print_shear(summary, outcome, wall_seconds),
        }
        outln!("outputs in {}/", out.display());
        outln!(
            "  summary.json, curve.csv, fields.npz{}",
            if options.fields.is_some() { ", fields.nc" } else { "" }
        );
        outln!("  {}", done.plot_files.join(", "));
        if matches!(outcome.report, RunSummary::Indentation(_)) {
            outln!(
                "  snapshots/: {} contact maps (largest_contact.png, max_depth.png, pull_off.png, jump_*.png, step_*.png)",
                done.snapshot_files.len()
            );
        }
    }
    Ok(())
}

fn print_indentation(scenario: &ValidScenario, summary: &ProtocolSummary, wall_seconds: f64) {
    outln!("adhesim: {} steps in {:.1} s", summary.steps, wall_seconds);
    if let Some(jkr) = scenario.jkr {
        outln!(
            "  max adhesive force = {:.4} |F_JKR|, jumps = {}",
            summary.max_adhesive_force / jkr.critical_force().abs(),
            summary.jumps
        );
    }
}

fn print_shear(summary: &ShearSummary, outcome: &RunOutcome, wall_seconds: f64) {
    outln!("adhesim: shear {} steps in {:.1} s", summary.steps, wall_seconds);
    let RunResults::Shear(results) = &outcome.results else {
        return;
    };
    outln!(
        "  F_N = {:.4e}, peak F_T = {:.4e} ({:.4} F_N), contact area {:.4e}",
        summary.normal_force,
        summary.peak_tangential_force,
        summary.peak_tangential_force / summary.normal_force,
        summary.area
    );
    match results.mean_shear_stress {
        Some(tau) => outln!(
            "  gross slip: sliding F_T = {:.4e}, τ = F_T/A = {tau:.4e}",
            summary.final_tangential_force
        ),
        None => outln!("  no gross slip at the end of the stroke"),
    }
    if results.slip_events > 0 {
        outln!(
            "  {} slip events (the force fell as the contact broke loose, then stuck again)",
            results.slip_events
        );
    }
    if results.contact_area_reduction != 1.0 {
        outln!(
            "  contact area at the peak / at rest = {:.4}",
            results.contact_area_reduction
        );
    }
    if let Some(shift) = results.contact_lost_at_shift {
        outln!(
            "  contact lost at shift {shift:.4e}; most tensile normal force {:.4e}",
            results.min_normal_force
        );
    }
    outln!(
        "  frictional dissipation {:.4e}; {} tangential rounds, {} FFT pairs",
        summary.frictional_dissipation,
        summary.tangential_rounds,
        summary.tangential_transform_pairs
    );
}

fn print_translation(scenario: &ValidScenario, summary: &TranslationSummary, outcome: &RunOutcome, wall_seconds: f64) {
    let ProtocolSetup::Translation(setup) = scenario.protocol_setup() else {
        return;
    };
    let RunResults::Translation(results) = &outcome.results else {
        return;
    };
    outln!(
        "adhesim: {} {} steps ({} moving) in {:.1} s",
        setup.kind.name(),
        summary.steps,
        summary.steps - setup.protocol.approach_steps,
        wall_seconds
    );
    let force = scenario.jkr.map_or(1.0, |j| j.critical_force().abs());
    let unit = if scenario.jkr.is_some() { " |F_JKR|" } else { "" };
    outln!(
        "  mean F_T = {:.4e}{unit} (per step), {:.4e}{unit} (work), fluctuation {:.4e}{unit}, mean F_N = {:.4e}{unit}",
        summary.mean_tangential_force / force,
        summary.mean_tangential_force_work / force,
        summary.tangential_force_fluctuation / force,
        summary.mean_normal_force / force,
    );
    if let Some(interface) = results.interface_friction_force {
        outln!(
            "  friction at the interface: {:.4e}{unit} of F_T (its dissipation per distance), {:.4e} dissipated",
            interface / force,
            summary.frictional_dissipation
        );
    }
    if let (Some(p), Some(r)) = (results.eq12_prediction, results.eq12_ratio) {
        outln!("  Eq. 12: 2a(γ2−γ1) = {:.4}{unit}, F_T / 2a(γ2−γ1) = {r:.3}", p / force);
    }
    outln!(
        "  half-width a = {:.4e}, compactness A/(πa²) = {:.3}, jumps = {}",
        results.contact_half_width,
        results.compactness,
        results.jumps
    );
}
