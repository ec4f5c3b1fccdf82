//! `adhesim study rolling|sliding STUDY.toml [--out DIR] [--jobs N]`: the multi-run
//! studies of the paper's Figs. 7, 8 and 10 (docs/friction.md).
//!
//! A study file names a roll or slide scenario and the Johnson parameters α to visit
//! (indenter.amplitude is set from α at the scenario's λ, γ0, E*); rolling also lists
//! the depths d/|d_JKR| of the rolling runs and the indent_pulloff run per α that gives
//! γ1, γ2 for Eq. 12. Cases run in parallel; the study writes `table.csv` (one row per
//! rolling/sliding case), `alphas.csv` (one row per α), `study.json` and the figures in
//! `plots/`.

mod plots;
mod runs;
mod tables;

use adhesim::analysis::johnson::amplitude_for_johnson_parameter;
use adhesim::analysis::reference::Jkr;
use adhesim_scenario::batch::{self, Batch, BatchCase, CaseState};
use adhesim_scenario::{self as scenario, ProtocolKind, ValidScenario};
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, ValueEnum};
use plots::{rolling_plots, sliding_plots};
use runs::{CaseRecord, NormalRecord, RunKind, StudyRun, ROLLING_ANALYSIS};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;
use tables::{theta_label, write_csv, AlphaRow, Row};

/// Which study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StudyKind {
    /// Figs. 7 and 8: rolling friction vs Eq. 12, γ3 vs α.
    Rolling,
    /// Fig. 10: sliding boundary friction and compactness vs α.
    Sliding,
}

#[derive(Args)]
pub struct StudyArgs {
    /// rolling (Figs. 7, 8) or sliding (Fig. 10).
    pub kind: StudyKind,
    /// Study file (TOML).
    pub study: PathBuf,
    /// Output folder [default: out/<study file stem>/].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Cases run at the same time.
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// No progress lines.
    #[arg(long)]
    pub quiet: bool,
    /// Run only the runs whose index modulo N is I (0-based; normal runs first, then the
    /// cases), e.g. one task of a cluster array job; the command that finds every run
    /// finished writes the tables and figures.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Wall time between mid-run checkpoints of a running run (0: none); a killed run goes
    /// on from its last checkpoint when the study is run again (docs/sweeps.md).
    #[arg(long, value_name = "SECONDS", default_value_t = batch::DEFAULT_CHECKPOINT_SECONDS)]
    pub checkpoint_every: f64,
    /// Run nothing: write the tables and figures of the α whose runs have all finished
    /// (interim results of a long study; safe beside the study running in the same folder,
    /// which it does not lock).
    #[arg(long)]
    pub tables_only: bool,
}

/// The study file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    /// rolling or sliding (must match the command line).
    pub kind: StudyKind,
    /// Scenario of kind roll (rolling) or slide (sliding), relative to the study file.
    pub base: PathBuf,
    /// Johnson parameters α = √(2λγ0/(π²h²E*)); h is set from each.
    pub alphas: Vec<f64>,
    /// Depths d/|d_JKR| of the translation runs [default: the base scenario's depth].
    #[serde(default)]
    pub depths: Vec<f64>,
    /// sliding: substrate orientations θ (degrees) to run every case at; the per-α means
    /// average over them and their spread gives the standard error of Fig. 10a (each θ is
    /// an independent incommensurate substrate) [default: the base scenario's θ].
    #[serde(default)]
    pub substrate_angles: Vec<f64>,
    /// Overrides `KEY=VALUE` applied to every case (as `--set`).
    #[serde(default)]
    pub set: Vec<String>,
    /// rolling: the indent_pulloff run per α that gives γ1, γ2.
    #[serde(default)]
    pub normal: NormalRun,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalRun {
    /// d_max/|d_JKR| of the normal run.
    pub max_depth: f64,
    /// Approach steps of the normal run.
    pub steps: i64,
}

impl Default for NormalRun {
    fn default() -> Self {
        Self {
            max_depth: 13.0,
            steps: 150,
        }
    }
}

/// Builds a validated scenario from the base table with `changes` applied.
fn build(table: &toml::Table, base_dir: &Path, changes: &[String]) -> Result<ValidScenario> {
    let mut table = table.clone();
    scenario::apply_overrides(&mut table, changes)?;
    let file = scenario::deserialize(&table)?;
    if let Some(limit) = crate::resources::memory_limit(false)? {
        file.check_memory(&limit, 1)?;
    }
    Ok(file.validate(base_dir)?)
}

/// The indent_pulloff case of a rolling study: the base with its protocol replaced.
fn normal_table(table: &toml::Table, normal: &NormalRun) -> toml::Table {
    let mut table = table.clone();
    table.remove("analysis");
    let mut protocol = toml::Table::new();
    protocol.insert("kind".into(), "indent_pulloff".into());
    protocol.insert("max_depth".into(), normal.max_depth.into());
    protocol.insert("depth_unit".into(), "jkr".into());
    protocol.insert("steps".into(), normal.steps.into());
    table.insert("protocol".into(), toml::Value::Table(protocol));
    table
}

/// A study ready to run: the base, the scales and every case, validated.
struct StudyPlan {
    study: StudyFile,
    wanted: ProtocolKind,
    jkr: Jkr,
    amplitudes: Vec<f64>,
    /// The normal runs (rolling only), then the translation cases.
    runs: Vec<StudyRun>,
    out: PathBuf,
}

/// Reads the study file and checks its own keys.
fn read_study(args: &StudyArgs) -> Result<(StudyFile, String)> {
    let text = scenario::read_input_text(&args.study, "study file")?;
    let origin = args.study.display().to_string();
    let study: StudyFile = toml::from_str(&text).map_err(|e| anyhow!("{origin}: {}", e.message().trim()))?;
    if study.kind != args.kind {
        bail!(
            "{origin}: kind = {:?} but the command asks for {:?}",
            study.kind,
            args.kind
        );
    }
    if args.jobs == 0 {
        bail!("--jobs must be >= 1, got 0");
    }
    if study.alphas.is_empty() || study.alphas.iter().any(|a| !(a.is_finite() && *a > 0.0)) {
        bail!(
            "{origin}: alphas must be a non-empty list of numbers > 0, got {:?}",
            study.alphas
        );
    }
    if study.depths.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
        bail!("{origin}: depths must be numbers > 0, got {:?}", study.depths);
    }
    if !study.substrate_angles.is_empty() && study.kind != StudyKind::Sliding {
        bail!("{origin}: substrate_angles is a key of sliding studies only");
    }
    if study.substrate_angles.iter().any(|a| !a.is_finite()) {
        bail!(
            "{origin}: substrate_angles must be finite numbers (degrees), got {:?}",
            study.substrate_angles
        );
    }
    Ok((study, origin))
}

/// Validates the base and every case before running any.
fn plan(args: &StudyArgs, study: StudyFile) -> Result<StudyPlan> {
    let study_dir = args.study.parent().unwrap_or(Path::new("."));
    let base_path = study_dir.join(&study.base);
    let base_text = scenario::read_input_text(
        &base_path,
        &format!("the base scenario (base = {})", study.base.display()),
    )?;
    let base_dir = base_path.parent().unwrap_or(Path::new(".")).to_path_buf();
    let mut table = scenario::parse_toml(&base_text, &base_path.display().to_string())?;
    scenario::apply_overrides(&mut table, &study.set).context("set")?;
    let base = build(&table, &base_dir, &[]).with_context(|| format!("base = {}", study.base.display()))?;
    let wanted = match study.kind {
        StudyKind::Rolling => ProtocolKind::Roll,
        StudyKind::Sliding => ProtocolKind::Slide,
    };
    let setup = base.translation.filter(|t| t.kind == wanted).ok_or_else(|| {
        anyhow!(
            "base = {}: needs protocol.kind = \"{}\"",
            study.base.display(),
            wanted.name()
        )
    })?;
    let (_, wavelength) = base
        .file
        .indenter
        .waviness()
        .ok_or_else(|| anyhow!("base = {}: needs a wavy_sphere indenter", study.base.display()))?;
    let jkr = base
        .jkr
        .ok_or_else(|| anyhow!("base = {}: needs adhesion.work_of_adhesion > 0", study.base.display()))?;
    let gamma0 = jkr.work_of_adhesion;
    let depths: Vec<f64> = if study.depths.is_empty() {
        vec![setup.protocol.depth / jkr.critical_depth().abs()]
    } else {
        study.depths.clone()
    };
    let out = match &args.out {
        Some(out) => out.clone(),
        None => Path::new("out").join(args.study.file_stem().unwrap_or_default()),
    };
    std::fs::create_dir_all(out.join("plots")).with_context(|| format!("cannot create {}", out.display()))?;
    let amplitudes: Vec<f64> = study
        .alphas
        .iter()
        .map(|&a| amplitude_for_johnson_parameter(a, wavelength, gamma0, jkr.contact_modulus))
        .collect();
    // Sliding cases carry their substrate angle; the base's angle is not written as an
    // override, so its runs are those of a study without `substrate_angles`.
    let base_angle = (study.kind == StudyKind::Sliding).then(|| {
        base.file
            .protocol
            .motion()
            .and_then(|(_, substrate_angle)| substrate_angle)
            .unwrap_or(scenario::DEFAULT_SUBSTRATE_ANGLE)
    });
    let angles: Vec<Option<f64>> = match base_angle {
        Some(_) if !study.substrate_angles.is_empty() => study.substrate_angles.iter().map(|&a| Some(a)).collect(),
        other => vec![other],
    };
    // Validate every case before running any.
    let mut runs = Vec::new();
    if study.kind == StudyKind::Rolling {
        let normal = normal_table(&table, &study.normal);
        for (i, &h) in amplitudes.iter().enumerate() {
            let changes = [format!("indenter.amplitude={h:e}")];
            let scenario =
                build(&normal, &base_dir, &changes).context("the normal (indent_pulloff) run of the study")?;
            let mut run = StudyRun::new(&format!("normal-{i}"), &normal, &changes, scenario, RunKind::Normal);
            run.what = format!("normal run α = {}", study.alphas[i]);
            run.progress = !args.quiet;
            run.alpha_index = i;
            runs.push(run);
        }
    }
    for (i, &h) in amplitudes.iter().enumerate() {
        for (j, &d) in depths.iter().enumerate() {
            for &angle in &angles {
                let mut changes = vec![
                    format!("indenter.amplitude={h:e}"),
                    format!("protocol.depth={d:e}"),
                    "protocol.depth_unit=\"jkr\"".to_string(),
                ];
                let mut name = format!("case-{i}-{j}");
                if let Some(theta) = angle.filter(|&a| Some(a) != base_angle) {
                    changes.push(format!("protocol.substrate_angle={theta:e}"));
                    name.push_str(&format!("-theta{theta}"));
                }
                let scenario = build(&table, &base_dir, &changes)
                    .with_context(|| format!("case α = {}, d = {d}·|d_JKR|{}", study.alphas[i], theta_label(angle)))?;
                let mut key = changes.clone();
                if study.kind == StudyKind::Rolling {
                    key.push(ROLLING_ANALYSIS.to_string());
                }
                let mut run = StudyRun::new(&name, &table, &key, scenario, RunKind::Translation);
                let shown_angle = angle.filter(|_| angles.len() > 1);
                run.what = format!(
                    "{} α = {}, d = {d}·|d_JKR|{}",
                    wanted.name(),
                    study.alphas[i],
                    theta_label(shown_angle)
                );
                (run.alpha_index, run.depth, run.angle) = (i, d, angle);
                run.progress = !args.quiet;
                runs.push(run);
            }
        }
    }
    Ok(StudyPlan {
        study,
        wanted,
        jkr,
        amplitudes,
        runs,
        out,
    })
}

/// Runs the study's runs that are not finished in its folder on `--jobs` workers (one
/// thread each, as `--jobs` is the study's whole thread budget); a failed run is redone by
/// the next command.
fn execute(plan: &StudyPlan, args: &StudyArgs, batch: &Batch, start: Instant) -> Result<()> {
    let pending = batch.pending(&plan.runs, true)?;
    let total = pending.selected;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let report = |what: &str| {
        let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if !args.quiet {
            eprintln!("[{k}/{total}] {what} ({:.0} s)", start.elapsed().as_secs_f64());
        }
    };
    for run in &pending.finished {
        report(&format!("{} (finished earlier)", run.what));
    }
    let finished = |run: &StudyRun, failure: Option<&str>| match failure {
        None => report(&run.what),
        Some(message) => eprintln!("{} failed: {message}", run.what),
    };
    let outcome = batch.execute(pending, args.jobs, 1, &finished)?;
    outcome.failure_status(&plan.out, "study runs")
}

/// The results of every run, read from the case folders: (γ1, γ2, wall time) of each α's
/// normal run, the (α index, depth, angle) and (results, wall time) of each case.
type Finished = (
    Vec<(Option<f64>, Option<f64>, Option<f64>)>,
    Vec<(usize, f64, Option<f64>)>,
    Vec<(adhesim_scenario::TranslationResults, f64)>,
);

/// Reads the runs of the α marked in `complete`.
fn read_runs(plan: &StudyPlan, complete: &[bool]) -> Result<Finished> {
    let mut gammas = vec![(None, None, None); plan.amplitudes.len()];
    let (mut keys, mut results) = (Vec::new(), Vec::new());
    for run in plan.runs.iter().filter(|run| complete[run.alpha_index]) {
        let folder = plan.out.join("cases").join(&run.id);
        match run.kind {
            RunKind::Normal => {
                let record: NormalRecord = runs::load(&folder)?;
                gammas[run.alpha_index] = (record.gamma_approach, record.gamma_pulloff, Some(record.wall_seconds));
            }
            RunKind::Translation => {
                let record: CaseRecord = runs::load(&folder)?;
                keys.push((run.alpha_index, run.depth, run.angle));
                results.push((record.results, record.wall_seconds));
            }
        }
    }
    Ok((gammas, keys, results))
}

/// Runs a study.
pub fn run(args: &StudyArgs) -> Result<()> {
    let start = Instant::now();
    let (study, _origin) = read_study(args)?;
    let plan = plan(args, study)?;
    if args.tables_only {
        return write_tables(&plan, args, start);
    }
    let shard = batch::parse_shard(args.shard.as_deref())?;
    let mut batch = Batch::open(&plan.out, shard)?;
    batch
        .set_checkpoint_seconds(args.checkpoint_every)
        .context("--checkpoint-every")?;
    let adopted = runs::adopt_old_cache(&plan.out, &plan.runs, &batch)?;
    if adopted > 0 && !args.quiet {
        eprintln!(
            "{adopted} finished runs of {}/cache/ (an older adhesim's layout) moved into case folders",
            plan.out.display()
        );
    }
    execute(&plan, args, &batch, start)?;
    let unfinished = plan
        .runs
        .iter()
        .filter(|run| batch::case_state(&plan.out, run.id(), run.hash()) != CaseState::Finished { ok: true })
        .count();
    if unfinished > 0 {
        // Only a shard ran: the tables need the other shards' runs.
        if !args.quiet {
            outln!(
                "adhesim study: shard {}/{} done; {unfinished} of {} runs are not finished yet: the command that \
                 finds them all finished (another shard, or the study without --shard) writes the tables",
                shard.index,
                shard.count,
                plan.runs.len()
            );
        }
        return Ok(());
    }
    write_tables(&plan, args, start)
}

/// Whether every run of each α has finished successfully.
fn complete_alphas(plan: &StudyPlan) -> Vec<bool> {
    (0..plan.amplitudes.len())
        .map(|i| {
            plan.runs
                .iter()
                .filter(|run| run.alpha_index == i)
                .all(|run| batch::case_state(&plan.out, run.id(), run.hash()) == CaseState::Finished { ok: true })
        })
        .collect()
}

/// Writes table.csv, alphas.csv, study.json and the figures from the α whose runs have
/// all finished (every α, after a whole study); study.json lists the others.
fn write_tables(plan: &StudyPlan, args: &StudyArgs, start: Instant) -> Result<()> {
    let complete = complete_alphas(plan);
    let pending: Vec<f64> = (plan.study.alphas.iter().zip(&complete))
        .filter(|(_, done)| !**done)
        .map(|(&alpha, _)| alpha)
        .collect();
    if pending.len() == complete.len() {
        eprintln!(
            "adhesim study: no α of {} has all its runs finished yet: no tables written",
            plan.out.display()
        );
        return Ok(());
    }
    let (gammas, case_keys, case_results) = read_runs(plan, &complete)?;
    let StudyPlan {
        study,
        jkr,
        amplitudes,
        out,
        ..
    } = plan;
    let jkr = *jkr;
    let (rows, per_case) = tables::case_rows(&case_keys, case_results, study, amplitudes, &gammas, &jkr);
    // One row per α of the study, in its order: the complete ones are kept.
    let alpha_rows: Vec<_> = tables::alpha_rows(study, amplitudes, &gammas, &rows, &per_case, &jkr)
        .into_iter()
        .zip(&complete)
        .filter_map(|(row, &done)| done.then_some(row))
        .collect();
    let a_jkr = jkr.critical_radius();
    write_csv(&out.join("table.csv"), &rows)?;
    write_csv(&out.join("alphas.csv"), &alpha_rows)?;
    let plots = match study.kind {
        StudyKind::Rolling => rolling_plots(&out.join("plots"), &rows, &alpha_rows)?,
        StudyKind::Sliding => sliding_plots(&out.join("plots"), &alpha_rows)?,
    };
    let json = serde_json::json!({
        "study": study,
        "f_jkr": jkr.critical_force(),
        "d_jkr": jkr.critical_depth(),
        "a_jkr": a_jkr,
        "cases": rows.len(),
        "normal_runs": plan.normal_runs(),
        // α whose runs are not all finished (an interim `--tables-only`): not in the tables.
        "unfinished_alphas": pending,
        "wall_seconds": start.elapsed().as_secs_f64(),
        "jobs": args.jobs,
        "alphas": alpha_rows,
    });
    batch::write_atomically(
        &out.join("study.json"),
        (serde_json::to_string_pretty(&json)? + "\n").as_bytes(),
    )?;
    if !args.quiet {
        print_report(plan, &rows, &alpha_rows, &plots, start);
        if !pending.is_empty() {
            outln!("  (interim: the runs of α = {pending:?} are not all finished; they are not in the tables)");
        }
    }
    Ok(())
}

impl StudyPlan {
    fn normal_runs(&self) -> usize {
        self.runs.iter().filter(|r| r.kind == RunKind::Normal).count()
    }
}

fn show(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| format!("{v:.3}"))
}

/// The study's report on stdout.
fn print_report(plan: &StudyPlan, rows: &[Row], alpha_rows: &[AlphaRow], plots: &[String], start: Instant) {
    let StudyPlan { study, wanted, out, .. } = plan;
    outln!(
        "adhesim study {}: {} cases + {} normal runs in {:.0} s",
        wanted.name(),
        rows.len(),
        plan.normal_runs(),
        start.elapsed().as_secs_f64()
    );
    for a in alpha_rows {
        match study.kind {
            StudyKind::Rolling => outln!(
                "  α = {:.3}: γ1/γ0 = {}, γ2/γ0 = {}, F_T/2a(γ2−γ1) = {} (per step), {} (work), γ3/γ0 = {}",
                a.alpha,
                show(a.gamma_approach_norm),
                show(a.gamma_pulloff_norm),
                show(a.mean_eq12_ratio),
                show(a.mean_eq12_ratio_work),
                show(a.gamma3_norm)
            ),
            StudyKind::Sliding => outln!(
                "  α = {:.3}: F_B/|F_JKR| = {} (per step), {} (work), F_B/(2aγ0) = {}{}, A/(πa²) = {:.3}",
                a.alpha,
                show(a.mean_tangential_force_norm),
                show(a.mean_tangential_force_work_norm),
                show(a.boundary_force_per_width_norm),
                a.boundary_force_per_width_sem
                    .map(|e| format!(" ± {e:.3} (standard error over cases)"))
                    .unwrap_or_default(),
                a.compactness
            ),
        }
    }
    outln!(
        "outputs in {}/: table.csv, alphas.csv, study.json, {}",
        out.display(),
        plots.join(", ")
    );
}
