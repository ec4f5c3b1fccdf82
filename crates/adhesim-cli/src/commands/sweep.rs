//! `adhesim sweep`: parameter studies of many scenarios (docs/sweeps.md).
//!
//! A sweep file names a base scenario and the keys to vary; the cases run in parallel
//! (`--jobs`), each into `DIR/cases/<id>/`, written atomically (a temporary folder under
//! `DIR/tmp/` renamed when the case is finished, with a `done` marker holding the case's
//! hash). A re-run skips finished cases and redoes broken ones; `--shard I/N` runs the
//! cases whose index modulo N is I. Every run (and `sweep merge DIR`) rebuilds
//! `DIR/table.csv` and the master-curve plots from all finished case folders.

pub mod plan;
pub mod table;

use crate::commands::batch::{self, write_atomically};
use crate::commands::folder::{FolderLock, Shard};
use crate::commands::run::{run, RunOptions};
use crate::resources;
use adhesim_scenario as scenario;
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use plan::{Case, Plan};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

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
    let out = match &args.out {
        Some(out) => out.clone(),
        None => {
            let stem = file
                .file_stem()
                .ok_or_else(|| anyhow!("sweep path {} has no file name", file.display()))?;
            Path::new("out").join(stem)
        }
    };
    if args.merge_only {
        return merge(&out, args.quiet);
    }
    let shard = parse_shard(args.shard.as_deref())?;
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
    if let Some(available) = resources::memory_limit(args.allow_large)? {
        check_memory(&plan, jobs, available)?;
    }
    execute(&plan, &out, shard, jobs, threads, args.quiet, args.retry_failed)
}

/// Refuses a plan whose largest grid, run `jobs` at a time, needs more memory than is
/// available (before any case allocates its FFT buffers).
fn check_memory(plan: &Plan, jobs: usize, available: u64) -> Result<()> {
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
    file.check_memory(available, runs)
        .with_context(|| format!("case {} (pass --allow-large to run anyway, or lower --jobs)", case.id))
}

/// Parses `I/N` with 0 <= I < N.
pub fn parse_shard(text: Option<&str>) -> Result<(usize, usize)> {
    let Some(text) = text else { return Ok((0, 1)) };
    let bad = || anyhow!("--shard expects I/N with 0 <= I < N (e.g. 0/4), got `{text}`");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// What a case folder's `done` marker says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CaseState {
    Missing,
    Finished {
        ok: bool,
    },
    /// A folder without a valid marker, or from a different scenario (another hash).
    Broken,
}

/// Reads `DIR/cases/<id>/done`.
pub fn case_state(dir: &Path, case: &Case) -> CaseState {
    let folder = dir.join("cases").join(&case.id);
    if !folder.exists() {
        return CaseState::Missing;
    }
    let Ok(text) = std::fs::read_to_string(folder.join("done")) else {
        return CaseState::Broken;
    };
    let field = |name: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(name).and_then(|r| r.strip_prefix(" = ")))
            .map(str::trim)
    };
    match (field("hash"), field("status")) {
        (Some(hash), Some(status)) if hash == case.hash => CaseState::Finished { ok: status == "ok" },
        _ => CaseState::Broken,
    }
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

fn execute(
    plan: &Plan,
    dir: &Path,
    (shard, shards): (usize, usize),
    jobs: usize,
    threads: usize,
    quiet: bool,
    retry_failed: bool,
) -> Result<()> {
    // Held until the end: a second command on the same cases is refused, not interleaved.
    let _lock = FolderLock::acquire(
        dir,
        Shard {
            index: shard,
            count: shards,
        },
    )?;
    write_plan(dir, plan)?;
    let temp_root = dir.join("tmp");
    std::fs::create_dir_all(&temp_root).with_context(|| format!("cannot create {}", temp_root.display()))?;
    let mine: Vec<&Case> = plan.cases.iter().filter(|c| c.index % shards == shard).collect();
    let mut todo = Vec::new();
    let mut skipped = 0;
    let mut kept_failures = Vec::new();
    for case in &mine {
        // Leftovers of a killed run of this case (only this shard's cases: other shards may
        // be running in the same folder).
        remove_temp_folders(&temp_root, &case.id);
        match case_state(dir, case) {
            CaseState::Finished { ok: true } => skipped += 1,
            CaseState::Finished { ok: false } if !retry_failed => {
                skipped += 1;
                kept_failures.push(case.id.clone());
            }
            CaseState::Broken | CaseState::Finished { .. } => {
                let folder = dir.join("cases").join(&case.id);
                std::fs::remove_dir_all(&folder).with_context(|| format!("cannot remove {}", folder.display()))?;
                todo.push(*case);
            }
            CaseState::Missing => todo.push(*case),
        }
    }
    let progress = if quiet || !std::io::stderr().is_terminal() || todo.is_empty() {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::with_draw_target(Some(todo.len() as u64), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} cases (eta {eta}) {msg}")
                .expect("valid template"),
        );
        bar.enable_steady_tick(std::time::Duration::from_millis(500));
        bar
    };
    let next = AtomicUsize::new(0);
    let failures = Mutex::new(Vec::new());
    let fatal: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(todo.len()) {
            scope.spawn(|| {
                let pool = match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
                    Ok(pool) => pool,
                    Err(e) => {
                        *fatal.lock().expect("lock") = Some(anyhow!("cannot build a thread pool: {e}"));
                        return;
                    }
                };
                loop {
                    if fatal.lock().expect("lock").is_some() {
                        return;
                    }
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some(case) = todo.get(k) else { return };
                    match run_case(plan, dir, case, &pool) {
                        Ok(None) => {}
                        Ok(Some(message)) => {
                            progress.suspend(|| eprintln!("case {} failed: {message}", case.id));
                            failures.lock().expect("lock").push(case.id.clone());
                        }
                        Err(error) => {
                            *fatal.lock().expect("lock") = Some(error.context(format!("case {}", case.id)));
                            return;
                        }
                    }
                    progress.inc(1);
                    progress.set_message(format!("last: {}", case.id));
                }
            });
        }
    });
    progress.finish_and_clear();
    if let Some(error) = fatal.into_inner().expect("lock") {
        // Keep what finished: rebuild the table before reporting.
        let _ = table::rebuild(dir, plan);
        return Err(error);
    }
    let summary = table::rebuild(dir, plan)?;
    let plots = crate::master_plots::from_sweep(dir, &summary.path).context("master-curve plots")?;
    let failures = failures.into_inner().expect("lock");
    if !quiet {
        println!(
            "adhesim sweep: {} cases in the plan, shard {shard}/{shards}: {} run now, {skipped} already finished, {} failed",
            plan.cases.len(),
            todo.len(),
            failures.len()
        );
        print_table_and_plots(dir, plan, &summary, &plots);
    }
    failure_status(dir, mine.len(), &failures, &kept_failures)
}

/// The sweep's exit: an error counting the failed cases of this run (and those kept from
/// an earlier run), so that a script notices; Ok when none failed.
fn failure_status(dir: &Path, cases: usize, failed_now: &[String], kept: &[String]) -> Result<()> {
    let total = failed_now.len() + kept.len();
    if total == 0 {
        return Ok(());
    }
    let list = |ids: &[String]| {
        let mut text = ids.iter().take(10).cloned().collect::<Vec<_>>().join(", ");
        if ids.len() > 10 {
            text.push_str(", ...");
        }
        text
    };
    let mut message = format!("{total} of {cases} cases failed");
    if !failed_now.is_empty() {
        message.push_str(&format!("; {} in this run: {}", failed_now.len(), list(failed_now)));
    }
    if !kept.is_empty() {
        message.push_str(&format!(
            "; {} failed earlier and were kept (--retry-failed redoes them): {}",
            kept.len(),
            list(kept)
        ));
    }
    bail!(
        "{message} (each case's error is in {}/cases/<id>/error.txt)",
        dir.display()
    )
}

fn remove_temp_folders(temp_root: &Path, id: &str) {
    let Ok(entries) = std::fs::read_dir(temp_root) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.strip_prefix(id).is_some_and(|rest| rest.starts_with('.')) {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

/// Runs one case into a temporary folder and renames it into place. `Ok(Some(message))`
/// is a failed case (recorded in its folder); `Err` is a failure of the sweep itself
/// (the output folder cannot be written).
fn run_case(plan: &Plan, dir: &Path, case: &Case, pool: &rayon::ThreadPool) -> Result<Option<String>> {
    let temp = dir.join("tmp").join(format!("{}.{}", case.id, std::process::id()));
    if temp.exists() {
        std::fs::remove_dir_all(&temp).with_context(|| format!("cannot remove {}", temp.display()))?;
    }
    std::fs::create_dir_all(&temp).with_context(|| format!("cannot create {}", temp.display()))?;
    std::fs::write(temp.join("scenario.toml"), &case.scenario)
        .with_context(|| format!("cannot write {}", temp.display()))?;
    let case_info = serde_json::json!({
        "index": case.index,
        "id": case.id,
        "hash": case.hash,
        "series": plan.series,
        "values": plan.keys.iter().zip(&case.values).map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone()))).collect::<serde_json::Map<_, _>>(),
    });
    std::fs::write(temp.join("case.json"), serde_json::to_string_pretty(&case_info)? + "\n")?;
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        pool.install(|| -> Result<()> {
            let scenario = scenario::load(&case.scenario, &format!("case {}", case.id), &plan.base_dir, &[])?;
            let options = RunOptions {
                quiet: true,
                ..RunOptions::default()
            };
            run(scenario, &temp, &options)
        })
    }));
    let failure = match outcome {
        Ok(Ok(())) => None,
        Ok(Err(error)) => Some(format!("{error:#}")),
        Err(panic) => Some(batch::panic_message(panic.as_ref())),
    };
    if let Some(message) = &failure {
        std::fs::write(temp.join("error.txt"), format!("{message}\n"))?;
    }
    let status = if failure.is_none() { "ok" } else { "error" };
    std::fs::write(temp.join("done"), format!("hash = {}\nstatus = {status}\n", case.hash))?;
    let target = dir.join("cases").join(&case.id);
    if target.exists() {
        if matches!(case_state(dir, case), CaseState::Finished { .. }) {
            // Someone else (a concurrent run of the same shard) finished it first.
            std::fs::remove_dir_all(&temp)?;
            return Ok(failure);
        }
        std::fs::remove_dir_all(&target).with_context(|| format!("cannot remove {}", target.display()))?;
    }
    std::fs::rename(&temp, &target)
        .with_context(|| format!("cannot move {} to {}", temp.display(), target.display()))?;
    Ok(failure)
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
