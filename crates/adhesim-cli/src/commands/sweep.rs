//! `adhesim sweep`: parameter studies of many scenarios (docs/sweeps.md).
//!
//! A sweep file names a base scenario and the keys to vary; the cases run on the batch
//! engine ([`adhesim_scenario::batch`]) in parallel (`--jobs`), each into `DIR/cases/<id>/`,
//! written atomically (a temporary folder under `DIR/tmp/` renamed when the case is
//! finished, with a `done` marker holding the case's hash). A re-run skips finished cases
//! and redoes broken ones; `--shard I/N` runs the cases whose index modulo N is I. Every run (and `sweep merge DIR`) rebuilds
//! `DIR/table.csv` and the master-curve plots from all finished case folders.

use crate::commands::run::{run, RunOptions};
use crate::resources;
use adhesim_scenario as scenario;
use adhesim_scenario::batch::{self, write_atomically, Batch, BatchCase};
use adhesim_scenario::output::folder::{self, FolderLock, Shard};
use adhesim_scenario::sweep::{plan, table};
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use plan::{Case, Plan};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

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
    /// more memory than is available (`MemAvailable` of /proc/meminfo).
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
        check_memory(&plan, jobs, &limit)?;
    }
    execute(&plan, &out, shard, jobs, threads, args.quiet, args.retry_failed)
}

/// Refuses a plan whose largest grid, run `jobs` at a time, needs more memory than is
/// available (before any case allocates its FFT buffers).
fn check_memory(plan: &Plan, jobs: usize, limit: &resources::MemoryLimit) -> Result<()> {
    let mut largest: Option<(u64, &Case, adhesim_scenario::ScenarioFile)> = None;
    for case in &plan.cases {
        let table = adhesim_scenario::parse_toml(&case.scenario, &case.id)?;
        let file = adhesim_scenario::deserialize(&table)?;
        let estimate = file.memory_estimate();
        if largest.as_ref().is_none_or(|(e, _, _)| estimate > *e) {
            largest = Some((estimate, case, file));
        }
    }
    let Some((_, case, file)) = largest else { return Ok(()) };
    let runs = jobs.min(plan.cases.len()) as u64;
    file.check_memory(limit, runs)
        .with_context(|| format!("case {} (pass --allow-large to run anyway, or lower --jobs)", case.id))
}

/// Writes `DIR/sweep.json` (the plan), refusing a folder that holds another sweep.
fn write_plan(dir: &Path, plan: &Plan) -> Result<()> {
    std::fs::create_dir_all(dir.join("cases")).with_context(|| format!("cannot create {}", dir.display()))?;
    let path = dir.join("sweep.json");
    let text = serde_json::to_string_pretty(plan)? + "\n";
    if let Ok(existing) = std::fs::read_to_string(&path) {
        let same = serde_json::from_str::<Plan>(&existing)
            .map(|old| {
                // The same cases, whatever results revision hashed them: finished cases of
                // an older revision are then redone (their markers' hashes differ).
                let same_case = |a: &Case, b: &Case| {
                    (a.index, &a.id, &a.values, &a.scenario) == (b.index, &b.id, &b.values, &b.scenario)
                };
                old.keys == plan.keys
                    && old.cases.len() == plan.cases.len()
                    && old.cases.iter().zip(&plan.cases).all(|(a, b)| same_case(a, b))
            })
            .unwrap_or(false);
        if !same {
            bail!(
                "{} holds a different sweep (its sweep.json lists other cases); choose another --out or delete that folder",
                dir.display()
            );
        }
        if existing == text {
            return Ok(());
        }
    }
    write_atomically(&path, text.as_bytes())
}

fn read_plan(dir: &Path) -> Result<Plan> {
    let path = dir.join("sweep.json");
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("cannot read {} (is {} a sweep folder?)", path.display(), dir.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not a sweep plan", path.display()))
}

/// One case of a sweep, as the batch engine runs it: `adhesim run` of the case's scenario
/// into its folder, with `scenario.toml` and `case.json` beside the run's files.
struct SweepCase<'a> {
    plan: &'a Plan,
    case: &'a Case,
}

impl BatchCase for SweepCase<'_> {
    fn id(&self) -> &str {
        &self.case.id
    }

    fn hash(&self) -> &str {
        &self.case.hash
    }

    fn describe(&self, folder: &Path) -> Result<()> {
        let (plan, case) = (self.plan, self.case);
        std::fs::write(folder.join("scenario.toml"), &case.scenario)
            .with_context(|| format!("cannot write {}", folder.display()))?;
        let values = plan.keys.iter().zip(&case.values);
        let case_info = serde_json::json!({
            "index": case.index,
            "id": case.id,
            "hash": case.hash,
            "series": plan.series,
            "values": values.map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone()))).collect::<serde_json::Map<_, _>>(),
        });
        std::fs::write(
            folder.join("case.json"),
            serde_json::to_string_pretty(&case_info)? + "\n",
        )?;
        Ok(())
    }

    fn run(&self, folder: &Path) -> Result<()> {
        let case = self.case;
        let scenario = scenario::load(&case.scenario, &format!("case {}", case.id), &self.plan.base_dir, &[])?;
        let options = RunOptions {
            quiet: true,
            ..RunOptions::default()
        };
        run(scenario, folder, &options)
    }
}

fn execute(
    plan: &Plan,
    dir: &Path,
    shard: Shard,
    jobs: usize,
    threads: usize,
    quiet: bool,
    retry_failed: bool,
) -> Result<()> {
    let batch = Batch::open(dir, shard)?;
    write_plan(dir, plan)?;
    let cases: Vec<SweepCase> = plan.cases.iter().map(|case| SweepCase { plan, case }).collect();
    let pending = batch.pending(&cases, retry_failed)?;
    let todo = pending.todo.len();
    let progress = if quiet || !std::io::stderr().is_terminal() || todo == 0 {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::with_draw_target(Some(todo as u64), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} cases (eta {eta}) {msg}")
                .expect("valid template"),
        );
        bar.enable_steady_tick(std::time::Duration::from_millis(500));
        bar
    };
    let finished = |case: &SweepCase, failure: Option<&str>| {
        if let Some(message) = failure {
            progress.suspend(|| eprintln!("case {} failed: {message}", case.case.id));
        }
        progress.inc(1);
        progress.set_message(format!("last: {}", case.case.id));
    };
    let outcome = batch.execute(pending, jobs, threads, &finished);
    progress.finish_and_clear();
    let outcome = match outcome {
        Ok(outcome) => outcome,
        Err(error) => {
            // Keep what finished: rebuild the table before reporting.
            let _ = table::rebuild(dir, plan);
            return Err(error);
        }
    };
    let summary = table::rebuild(dir, plan)?;
    let plots = crate::master_plots::from_sweep(dir, &summary.path).context("master-curve plots")?;
    if !quiet {
        println!(
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

/// The report on the table and the plots of a sweep.
fn print_table_and_plots(dir: &Path, plan: &Plan, summary: &table::TableSummary, plots: &[String]) {
    println!(
        "{}: {} of {} cases finished ({} with errors)",
        summary.path.display(),
        summary.finished,
        plan.cases.len(),
        summary.errors
    );
    println!("plots in {}/plots/: {}", dir.display(), plots.join(", "));
}

/// `adhesim sweep merge DIR`: rebuilds the table and the plots.
pub fn merge(dir: &Path, quiet: bool) -> Result<()> {
    let plan = read_plan(dir)?;
    let _lock = FolderLock::acquire(dir, Shard::ALL)?;
    let summary = table::rebuild(dir, &plan)?;
    let plots = crate::master_plots::from_sweep(dir, &summary.path).context("master-curve plots")?;
    if !quiet {
        print_table_and_plots(dir, &plan, &summary, &plots);
    }
    Ok(())
}
