//! `adhesim sweep`: parameter studies of many scenarios (docs/sweeps.md).
//!
//! A sweep file names a base scenario and the keys to vary; the cases run on the batch
//! engine ([`adhesim_scenario::batch`]) in parallel (`--jobs`), each into `DIR/cases/<id>/`,
//! written atomically (a temporary folder under `DIR/tmp/` renamed when the case is
//! finished, with a `done` marker holding the case's hash). A re-run skips finished cases
//! and redoes broken ones; `--shard I/N` runs the cases whose index modulo N is I. Every run (and `sweep merge DIR`) rebuilds
//! `DIR/table.csv` and the master-curve plots from all finished case folders.

use crate::commands::run::{run_with_progress, RunOptions};
use crate::resources;
use adhesim::StepRecord;
use adhesim_figures::master_plots::sweep_table_and_plots;
use adhesim_scenario::batch::{self, Batch};
use adhesim_scenario::output::checkpoint::CheckpointPolicy;
use adhesim_scenario::output::folder::{self, FolderLock, Shard};
use adhesim_scenario::output::observer::RunProgress;
use adhesim_scenario::sweep::{check_memory, plan, read_plan, table, write_plan, SweepCase};
use adhesim_scenario::ValidScenario;
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, Subcommand};
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget};
use plan::Plan;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// `adhesim sweep SWEEP.toml [--out DIR] [--jobs N] [--shard I/N]`, or `adhesim sweep merge DIR`.
#[derive(Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    action: Option<SweepAction>,
    /// Sweep file (TOML): base scenario, [vary], [zip], [random] (see docs/sweeps.md).
    #[arg(required = true)]
    file: Option<PathBuf>,
    /// Output folder [default: out/<sweep file stem>/].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Cases run at the same time [default: the number of cores].
    #[arg(long)]
    jobs: Option<usize>,
    /// FFT threads per case [default: cores / jobs, at least 1].
    #[arg(long)]
    threads: Option<usize>,
    /// Wall time between mid-case checkpoints of a running case (0: none); a killed case
    /// goes on from its last checkpoint when the sweep is run again (docs/sweeps.md).
    #[arg(long, value_name = "SECONDS", default_value_t = batch::DEFAULT_CHECKPOINT_SECONDS)]
    checkpoint_every: f64,
    /// Run only the cases whose index modulo N is I (0-based), e.g. a SLURM array task:
    /// `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// No progress bar and no report on stdout.
    #[arg(long)]
    quiet: bool,
    /// Only rebuild table.csv and the plots from the finished cases in DIR.
    #[arg(long)]
    merge_only: bool,
    /// Also redo cases that finished with an error.
    #[arg(long)]
    retry_failed: bool,
    /// Print the case list (id and varied values) and exit.
    #[arg(long)]
    list: bool,
    /// Run even when `--jobs` concurrent cases of the largest grid are estimated to need
    /// more memory than is available (`MemAvailable` of /proc/meminfo; not beyond the
    /// address-space limit of `ulimit -v`).
    #[arg(long)]
    allow_large: bool,
}

#[derive(Subcommand)]
enum SweepAction {
    /// Rebuild DIR/table.csv and DIR/plots/ from the finished case folders (e.g. after
    /// the shards of a cluster array job have finished).
    Merge {
        /// Sweep output folder (holds sweep.json and cases/).
        dir: PathBuf,
        /// No report on stdout.
        #[arg(long)]
        quiet: bool,
    },
}

/// Entry point of `adhesim sweep`.
pub fn command(args: &SweepArgs) -> Result<()> {
    if let Some(SweepAction::Merge { dir, quiet }) = &args.action {
        return merge(dir, *quiet);
    }
    let file = args.file.as_ref().ok_or_else(|| anyhow!("a sweep file is required"))?;
    let out = folder::output_dir(args.out.as_deref(), file, "sweep")?;
    if args.merge_only {
        return merge(&out, args.quiet);
    }
    let shard = batch::parse_shard(args.shard.as_deref())?;
    let plan = plan::load(file)?;
    if args.list {
        use std::io::Write;
        let mut stdout = std::io::stdout().lock();
        // A closed pipe (`| head`) is not an error.
        let _ = writeln!(stdout, "case,{}", plan.keys.join(","));
        for case in &plan.cases {
            let _ = writeln!(stdout, "{},{}", case.id, case.values.join(","));
        }
        return Ok(());
    }
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    let jobs = match args.jobs {
        Some(0) => bail!("--jobs must be >= 1, got 0"),
        Some(j) => j,
        None => cores,
    };
    let threads = match args.threads {
        Some(t) => resources::clamp_threads(t)?,
        None => (cores / jobs).max(1),
    };
    if let Some(limit) = resources::memory_limit(args.allow_large)? {
        check_memory(&plan, jobs, &limit, "--allow-large")?;
    }
    let resources = Resources {
        jobs,
        threads,
        checkpoint_seconds: args.checkpoint_every,
    };
    execute(&plan, &out, shard, resources, args.quiet, args.retry_failed)
}

/// How a sweep runs its cases.
struct Resources {
    jobs: usize,
    threads: usize,
    checkpoint_seconds: f64,
}

fn execute(plan: &Plan, dir: &Path, shard: Shard, resources: Resources, quiet: bool, retry_failed: bool) -> Result<()> {
    let Resources {
        jobs,
        threads,
        checkpoint_seconds,
    } = resources;
    let mut batch = Batch::open(dir, shard)?;
    batch
        .set_checkpoint_seconds(checkpoint_seconds)
        .context("--checkpoint-every")?;
    write_plan(dir, plan)?;
    // Shared with the runner, which a sweep case holds for good ('static).
    let progress = std::sync::Arc::new(SweepProgress::new(!crate::progress::drawn(quiet)));
    let runner = {
        let progress = progress.clone();
        move |scenario: &ValidScenario, folder: &Path, checkpoint: Option<&CheckpointPolicy>| {
            run_case_with(scenario, folder, checkpoint, &mut progress.case(scenario))
        }
    };
    let cases: Vec<SweepCase> = plan
        .cases
        .iter()
        .map(|case| SweepCase {
            plan,
            case,
            runner: &runner,
        })
        .collect();
    let pending = batch.pending(&cases, retry_failed)?;
    let todo = pending.todo.len();
    progress.start(todo);
    let finished = |case: &SweepCase, failure: Option<&str>| {
        if let Some(message) = failure {
            progress
                .cases
                .suspend(|| eprintln!("case {} failed: {message}", case.case.id));
        }
        progress.cases.inc(1);
        progress.cases.set_message(format!("last: {}", case.case.id));
    };
    let outcome = batch.execute(pending, jobs, threads, &finished);
    progress.finish();
    let outcome = match outcome {
        Ok(outcome) => outcome,
        Err(error) => {
            // Keep what finished: rebuild the table before reporting.
            let _ = table::rebuild(dir, plan);
            return Err(error);
        }
    };
    let (summary, plots) = sweep_table_and_plots(dir, plan)?;
    if !quiet {
        outln!(
            "adhesim sweep: {} cases in the plan, shard {}/{}: {} run now, {} already finished, {} failed",
            plan.cases.len(),
            shard.index,
            shard.count,
            outcome.ran,
            outcome.skipped,
            outcome.failed_now.len()
        );
        print_table_and_plots(dir, plan, &summary, &plots);
    }
    outcome.failure_status(dir, "cases")
}

/// Runs one sweep case's scenario into its folder (`adhesim run --quiet`, figures
/// included), its steps shown by `progress`.
fn run_case_with(
    scenario: &ValidScenario,
    folder: &Path,
    checkpoint: Option<&CheckpointPolicy>,
    progress: &mut (dyn RunProgress + Send),
) -> Result<()> {
    run_with_progress(scenario, folder, &case_options(checkpoint), progress)
}

fn case_options(checkpoint: Option<&CheckpointPolicy>) -> RunOptions {
    RunOptions {
        quiet: true,
        checkpoint: checkpoint.cloned(),
        ..RunOptions::default()
    }
}

/// The sweep's progress on stderr: a bar of whole cases and under it one of the steps of
/// the running cases (done out of planned, summed over them), so that a sweep of long
/// cases moves before its first case ends. Hidden when quiet or not on a terminal.
struct SweepProgress {
    multi: Option<MultiProgress>,
    cases: ProgressBar,
    steps: ProgressBar,
    running: AtomicUsize,
}

impl SweepProgress {
    fn new(hidden: bool) -> Self {
        // Hidden until `start` adds them to the multi-bar; the steps' length of 0 is added to
        // (a hidden bar's length is unknown, and inc_length keeps it so).
        let cases = crate::progress::bar(0, crate::progress::SWEEP_CASES, false);
        let steps = crate::progress::bar(0, crate::progress::SWEEP_STEPS, false);
        Self {
            multi: (!hidden).then(|| MultiProgress::with_draw_target(ProgressDrawTarget::stderr())),
            cases,
            steps,
            running: AtomicUsize::new(0),
        }
    }

    /// Shows the bars for `todo` cases (none when there are none to run).
    fn start(&self, todo: usize) {
        self.cases.set_length(todo as u64);
        if let (Some(multi), true) = (&self.multi, todo > 0) {
            multi.add(self.cases.clone());
            multi.add(self.steps.clone());
            self.cases.enable_steady_tick(std::time::Duration::from_millis(500));
        }
    }

    /// The progress of one case starting now.
    fn case(&self, scenario: &ValidScenario) -> CaseSteps<'_> {
        let planned = scenario.expected_steps() as u64;
        self.steps.inc_length(planned);
        let running = self.running.fetch_add(1, Ordering::Relaxed) + 1;
        self.steps.set_message(running_cases(running));
        CaseSteps {
            sweep: self,
            planned,
            done: 0,
        }
    }

    fn finish(&self) {
        self.steps.finish_and_clear();
        self.cases.finish_and_clear();
    }
}

fn running_cases(running: usize) -> String {
    format!("of {running} running case{}", if running == 1 { "" } else { "s" })
}

/// One running case's share of the steps' bar: its planned steps (the estimate of `adhesim
/// run`'s bar, raised when a case runs longer), its steps as they are solved (from its
/// step number: a case resumed from a checkpoint starts where it stopped), both taken
/// back when it ends.
struct CaseSteps<'a> {
    sweep: &'a SweepProgress,
    planned: u64,
    done: u64,
}

impl RunProgress for CaseSteps<'_> {
    fn step(&mut self, record: &StepRecord) -> Result<()> {
        let done = record.step as u64 + 1;
        if done > self.planned {
            self.sweep.steps.inc_length(done - self.planned);
            self.planned = done;
        }
        if done > self.done {
            self.sweep.steps.inc(done - self.done);
            self.done = done;
        }
        Ok(())
    }

    fn warning(&mut self, message: &str) {
        self.sweep.steps.suspend(|| eprintln!("warning: {message}"));
    }
}

impl Drop for CaseSteps<'_> {
    fn drop(&mut self) {
        let steps = &self.sweep.steps;
        steps.dec(self.done);
        steps.dec_length(self.planned);
        let running = self.sweep.running.fetch_sub(1, Ordering::Relaxed).saturating_sub(1);
        steps.set_message(running_cases(running));
    }
}

/// The report on the table and the plots of a sweep.
fn print_table_and_plots(dir: &Path, plan: &Plan, summary: &table::TableSummary, plots: &[String]) {
    outln!(
        "{}: {} of {} cases finished ({} with errors)",
        summary.path.display(),
        summary.finished,
        plan.cases.len(),
        summary.errors
    );
    outln!("plots in {}/plots/: {}", dir.display(), plots.join(", "));
}

/// `adhesim sweep merge DIR`: rebuilds the table and the plots.
pub fn merge(dir: &Path, quiet: bool) -> Result<()> {
    let plan = read_plan(dir)?;
    let _lock = FolderLock::acquire(dir, Shard::ALL)?;
    let (summary, plots) = sweep_table_and_plots(dir, &plan)?;
    if !quiet {
        print_table_and_plots(dir, &plan, &summary, &plots);
    }
    Ok(())
}
