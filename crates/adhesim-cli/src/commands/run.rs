//! `adhesim run` (and `adhesim` without a subcommand): one scenario through the library's
//! run pipeline (`adhesim_scenario::run`) with the CLI's observer writing `curve.csv`,
//! snapshots and the progress bar; then the figures of the protocol and `summary.json`.

use crate::{output, plots, resources, summary, tangential_plots};
use adhesim::analysis::reference::Hertz;
use adhesim::{Profile, ProtocolError, ProtocolSummary, StepRecord, TranslationSummary};
use adhesim_scenario::output::folder;
use adhesim_scenario::{
    ProtocolReport, ProtocolSetup, RunOutcome, RunResults, SnapshotPlan, SnapshotRecorder, TranslationSetup,
    ValidScenario,
};
use anyhow::{anyhow, Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The built-in default scenario (the paper's Fig. 1 case).
const DEFAULT_SCENARIO: &str = include_str!("../../../../scenarios/fig1.toml");

/// Consecutive steps shown in the snapshot strip of a translation by default.
const STRIP_FRAMES: usize = 4;

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
    /// (`MemAvailable` of /proc/meminfo), e.g. where swap or a lazy allocator makes it fit.
    #[arg(long)]
    pub allow_large: bool,
    /// Override a scenario key before validation, e.g. `--set grid.n=64` (repeatable;
    /// VALUE is a TOML value).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Also write the snapshot fields as NetCDF-3 (`fields.nc`) besides `fields.npz`.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub fields: Option<FieldsFormat>,
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
    run(scenario, &out, &RunOptions::default())
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
        if e.to_string().contains("of memory available") {
            e.context("refused before allocating (pass --allow-large to run anyway)")
        } else {
            e
        }
    })?;
    let out = folder::output_dir(args.out.as_deref(), path, "scenario")?;
    folder::prepare_run_folder(&out, args.force)?;
    run(scenario, &out, &args.options)
}

/// Runs a validated scenario into `out`: curve.csv, snapshots, plots, summary.json. `out`
/// is new, or made ready by [`folder::prepare_run_folder`]; it gets the run marker.
pub fn run(scenario: ValidScenario, out: &Path, options: &RunOptions) -> Result<()> {
    if let Some(threads) = options.threads {
        let threads = resources::clamp_threads(threads)?;
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .context("cannot set up the thread pool")?;
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create output folder {}", out.display()))?;
    folder::write_run_marker(out)?;
    for warning in &scenario.warnings {
        eprintln!("warning: {warning}");
    }
    let start = Instant::now();
    let plan = SnapshotPlan::new(&scenario);
    let strip = strip_steps(&scenario);
    let mut observer = output::RunObserver::new(
        out,
        scenario.grid,
        scenario.jkr,
        plan,
        scenario.expected_steps(),
        options.quiet,
    )?;
    observer.capture(strip);
    observer.fields = Some(adhesim_scenario::output::fields::FieldsRecorder::new(
        SnapshotRecorder::new(SnapshotPlan::new(&scenario)),
        options.fields == Some(FieldsFormat::Netcdf),
    ));
    let outcome = adhesim_scenario::run(&scenario, &mut observer);
    observer.finish(&scenario)?;
    let outcome = match outcome {
        Ok(outcome) => outcome,
        Err(ProtocolError::Interrupted(step)) => {
            let cause = observer.error.take().unwrap_or_else(|| anyhow!("interrupted"));
            return Err(cause.context(format!("run stopped at step {step}")));
        }
        Err(error) => {
            // One message, not an error chain: `ProtocolError::Solve` shows its source in its
            // own text, so `{:#}` (here, in sweep's error.txt) would print it twice.
            return Err(
                anyhow!(adhesim_scenario::error_text::error_line(anyhow::Chain::new(&error))).context(format!(
                    "run failed; {} holds the steps done",
                    out.join("curve.csv").display()
                )),
            );
        }
    };
    let plot_files = match (&outcome.report, scenario.protocol_setup()) {
        (ProtocolReport::Translation(summary), ProtocolSetup::Translation(setup)) => translation_plots(
            &scenario,
            setup,
            summary,
            &outcome.records,
            &observer,
            &out.join("plots"),
        )?,
        _ => indentation_plots(&scenario, &outcome, &out.join("plots"))?,
    };
    let wall_seconds = start.elapsed().as_secs_f64();
    let counters = outcome.report.counters();
    let performance = summary::performance(wall_seconds, &counters, &observer);
    let summary = adhesim_scenario::Summary::new(&scenario, &outcome, performance, &observer.warnings);
    if let Some(warning) = adhesim_scenario::lost_contact_warning(&outcome.records) {
        eprintln!("warning: {warning}");
    }
    summary::write(&out.join("summary.json"), &summary)?;
    if !options.quiet {
        match &outcome.report {
            ProtocolReport::Indentation(summary) => print_indentation(&scenario, summary, wall_seconds),
            ProtocolReport::Translation(summary) => print_translation(&scenario, summary, &outcome, wall_seconds),
        }
        println!("outputs in {}/", out.display());
        println!(
            "  summary.json, curve.csv, fields.npz{}",
            if options.fields.is_some() { ", fields.nc" } else { "" }
        );
        println!("  {}", plot_files.join(", "));
        if matches!(outcome.report, ProtocolReport::Indentation(_)) {
            println!(
                "  snapshots/: {} contact maps (largest_contact.png, max_depth.png, pull_off.png, jump_*.png, step_*.png)",
                observer.snapshot_files.len()
            );
        }
    }
    Ok(())
}

/// The steps whose contact sets the observer keeps for the snapshot strip of a
/// translation (paper Figs. 6b, 9): the chosen steps (at most 8), else consecutive steps
/// in the middle of the stationary part.
fn strip_steps(scenario: &ValidScenario) -> Vec<usize> {
    let o = &scenario.file.output;
    let ProtocolSetup::Translation(setup) = scenario.protocol_setup() else {
        return Vec::new();
    };
    let protocol = &setup.protocol;
    let forward_end = protocol.approach_steps + protocol.steps;
    if o.snapshot_steps.is_empty() {
        let first = protocol.approach_steps
            + ((protocol.stationary_from + 0.5 * (1.0 - protocol.stationary_from)) * protocol.steps as f64) as usize;
        (first..first + STRIP_FRAMES).filter(|&s| s < forward_end).collect()
    } else {
        o.snapshot_steps.iter().map(|&s| s as usize).take(8).collect()
    }
}

/// The force–depth and force–radius figures of an indentation (with Hertz or JKR
/// references and the fitted JKR curves of γ1, γ2).
fn indentation_plots(scenario: &ValidScenario, outcome: &RunOutcome, dir: &Path) -> Result<Vec<String>> {
    let hertz = match (scenario.gamma0 > 0.0, scenario.indenter.radius_of_curvature()) {
        (false, Some(radius)) => Some(Hertz {
            radius,
            contact_modulus: scenario.material.contact_modulus(),
        }),
        _ => None,
    };
    let figures = plots::figures(
        &outcome.records,
        &plots::PlotContext {
            jkr: scenario.jkr,
            hertz,
            max_depth: scenario.max_depth,
        },
    );
    let overlays = match (scenario.jkr, &outcome.results) {
        (Some(jkr), RunResults::Indentation(results)) => vec![(
            "force_radius",
            plots::fitted_jkr_overlays(
                &jkr,
                &outcome.records,
                results.fits.gamma_approach,
                results.fits.gamma_pulloff,
            ),
        )],
        _ => Vec::new(),
    };
    plots::write_all_with_overlays(dir, &figures, &overlays)
}

/// The force–distance figure of a translation (Fig. 6a) and the strip of consecutive
/// contact maps (Figs. 6b, 9).
fn translation_plots(
    scenario: &ValidScenario,
    setup: &TranslationSetup,
    summary: &TranslationSummary,
    records: &[StepRecord],
    observer: &output::RunObserver,
    dir: &Path,
) -> Result<Vec<String>> {
    let protocol = &setup.protocol;
    let charts = tangential_plots::force_distance(
        records,
        scenario.jkr,
        setup.wavelength,
        (summary.mean_tangential_force, summary.mean_tangential_force_work),
        protocol.stationary_from * protocol.distance,
    );
    let mut plot_files = tangential_plots::write_panels(dir, "force_distance", &charts)?;
    if !observer.captured.is_empty() {
        let frames: Vec<(Vec<bool>, Vec<bool>, f64)> = observer
            .captured
            .iter()
            .map(|(step, contact, previous)| {
                let offset = records.get(*step).map_or(0.0, |r| r.offset);
                (contact.clone(), previous.clone(), offset)
            })
            .collect();
        tangential_plots::write_snapshot_strip(&dir.join("contact_snapshots.png"), &scenario.grid, &frames)?;
        plot_files.push("plots/contact_snapshots.png".into());
    }
    Ok(plot_files)
}

fn print_indentation(scenario: &ValidScenario, summary: &ProtocolSummary, wall_seconds: f64) {
    println!("adhesim: {} steps in {:.1} s", summary.steps, wall_seconds);
    if let Some(jkr) = scenario.jkr {
        println!(
            "  max adhesive force = {:.4} |F_JKR|, jumps = {}",
            summary.max_adhesive_force / jkr.critical_force().abs(),
            summary.jumps
        );
    }
}

fn print_translation(scenario: &ValidScenario, summary: &TranslationSummary, outcome: &RunOutcome, wall_seconds: f64) {
    let ProtocolSetup::Translation(setup) = scenario.protocol_setup() else {
        return;
    };
    let RunResults::Translation(results) = &outcome.results else {
        return;
    };
    println!(
        "adhesim: {} {} steps ({} moving) in {:.1} s",
        setup.kind.name(),
        summary.steps,
        summary.steps - setup.protocol.approach_steps,
        wall_seconds
    );
    let force = scenario.jkr.map_or(1.0, |j| j.critical_force().abs());
    let unit = if scenario.jkr.is_some() { " |F_JKR|" } else { "" };
    println!(
        "  mean F_T = {:.4}{unit} (per step), {:.4}{unit} (work), fluctuation {:.4}{unit}, mean F_N = {:.4}{unit}",
        summary.mean_tangential_force / force,
        summary.mean_tangential_force_work / force,
        summary.tangential_force_fluctuation / force,
        summary.mean_normal_force / force,
    );
    if let (Some(p), Some(r)) = (results.eq12_prediction, results.eq12_ratio) {
        println!("  Eq. 12: 2a(γ2−γ1) = {:.4}{unit}, F_T / 2a(γ2−γ1) = {r:.3}", p / force);
    }
    println!(
        "  half-width a = {:.4e}, compactness A/(πa²) = {:.3}, jumps = {}",
        results.contact_half_width, results.compactness, results.jumps
    );
}
