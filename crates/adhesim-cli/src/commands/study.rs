//! `adhesim study rolling|sliding STUDY.toml [--out DIR] [--jobs N]`: the multi-run
//! studies of the paper's Figs. 7, 8 and 10 (docs/friction.md).
//!
//! A study file names a roll or slide scenario and the Johnson parameters α to visit
//! (indenter.amplitude is set from α at the scenario's λ, γ0, E*); rolling also lists
//! the depths d/|d_JKR| of the rolling runs and the indent_pulloff run per α that gives
//! γ1, γ2 for Eq. 12. Cases run in parallel; the study writes `table.csv` (one row per
//! rolling/sliding case), `alphas.csv` (one row per α), `study.json` and the figures in
//! `plots/`.

use adhesim_scenario::{self as scenario, ProtocolKind, RunResults, TranslationResults, ValidScenario};
use crate::tangential_plots::{write_panels, Chart, Series, Style, PALETTE};
use adhesim::analysis::fit::fit_jkr_work_of_adhesion;
use adhesim::analysis::friction::eq12_rolling_resistance;
use adhesim::analysis::johnson::amplitude_for_johnson_parameter;
use anyhow::{anyhow, bail, Context, Result};
use clap::{Args, ValueEnum};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

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
    /// Cases run at the same time [default: 1].
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// No progress lines.
    #[arg(long)]
    pub quiet: bool,
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

/// One translation case's row of `table.csv`.
#[derive(Debug, Clone, Serialize)]
struct Row {
    alpha: f64,
    amplitude: f64,
    depth_norm: f64,
    /// Sliding: substrate orientation θ in degrees (empty for rolling).
    substrate_angle: Option<f64>,
    gamma_approach_norm: Option<f64>,
    gamma_pulloff_norm: Option<f64>,
    mean_tangential_force_norm: Option<f64>,
    mean_tangential_force_work_norm: Option<f64>,
    tangential_force_fluctuation_norm: Option<f64>,
    eq12_prediction_norm: Option<f64>,
    eq12_ratio: Option<f64>,
    eq12_ratio_work: Option<f64>,
    mean_normal_force_norm: Option<f64>,
    contact_half_width_norm: Option<f64>,
    contact_radius_norm: Option<f64>,
    compactness: f64,
    boundary_force_per_width_norm: Option<f64>,
    gamma3_norm: Option<f64>,
    gamma3_half_width_norm: Option<f64>,
    energy_balance_ratio: Option<f64>,
    jumps: usize,
    border_contact: bool,
    wall_seconds: f64,
}

/// One α's row of `alphas.csv`.
#[derive(Debug, Clone, Serialize)]
struct AlphaRow {
    alpha: f64,
    amplitude: f64,
    gamma_approach_norm: Option<f64>,
    gamma_pulloff_norm: Option<f64>,
    normal_wall_seconds: Option<f64>,
    /// γ3/γ0: JKR fit of F_N vs the contact radius (farthest element, as for γ1 and γ2)
    /// over all depths (Fig. 8).
    gamma3_norm: Option<f64>,
    /// The same fit against the half-width perpendicular to the motion.
    gamma3_half_width_norm: Option<f64>,
    /// Mean over depths of the per-step F_T / 2a(γ2 − γ1).
    mean_eq12_ratio: Option<f64>,
    mean_eq12_ratio_work: Option<f64>,
    /// Mean over depths of F_T/|F_JKR| (Fig. 10a).
    mean_tangential_force_norm: Option<f64>,
    mean_tangential_force_work_norm: Option<f64>,
    /// Mean over depths (and substrate angles) of F_T/(2a γ0).
    boundary_force_per_width_norm: Option<f64>,
    /// Standard error of that mean over the cases (spread/√n, n ≥ 2 cases).
    boundary_force_per_width_sem: Option<f64>,
    /// Standard error of mean_tangential_force_norm over the cases.
    mean_tangential_force_sem: Option<f64>,
    /// Mean over depths of A_real/(πa²) (Fig. 10b).
    compactness: f64,
}

/// Builds a validated scenario from the base table with `changes` applied.
fn build(table: &toml::Table, base_dir: &Path, changes: &[String]) -> Result<ValidScenario> {
    let mut table = table.clone();
    scenario::apply_overrides(&mut table, changes)?;
    scenario::deserialize(&table)?.validate(base_dir)
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

/// γ1, γ2 of an indent_pulloff run (the same pipeline and fits as `adhesim run`).
fn normal_gammas(scenario: &ValidScenario) -> Result<(Option<f64>, Option<f64>)> {
    match adhesim_scenario::run(scenario, &mut ()).map_err(|e| anyhow!(e))?.results {
        RunResults::Indentation(results) => Ok((results.fits.gamma_approach, results.fits.gamma_pulloff)),
        RunResults::Translation(_) => bail!("the normal run of a study must be protocol.kind = \"indent_pulloff\""),
    }
}

/// The analysed results of a roll / slide run, without writing anything.
fn translation_results(scenario: &ValidScenario) -> Result<TranslationResults> {
    match adhesim_scenario::run(scenario, &mut ()).map_err(|e| anyhow!(e))?.results {
        RunResults::Translation(results) => Ok(results),
        RunResults::Indentation(_) => bail!("protocol.kind = \"indent_pulloff\" is not a translation"),
    }
}

/// Finished runs of a study are kept under `<out>/cache/` so that a killed study resumes
/// where it stopped: one JSON file per run, named by its kind, index and a hash of the
/// exact scenario it ran (base after `set`, plus the case's overrides) and of the library's
/// results revision, written atomically.
struct RunCache {
    folder: PathBuf,
}

impl RunCache {
    fn new(out: &Path) -> Result<Self> {
        let folder = out.join("cache");
        std::fs::create_dir_all(&folder).with_context(|| format!("cannot create {}", folder.display()))?;
        Ok(Self { folder })
    }

    fn path(&self, name: &str, table: &toml::Table, changes: &[String]) -> PathBuf {
        let text = format!("{table}\n{}", changes.join("\n"));
        self.folder
            .join(format!("{name}-{:016x}.json", crate::commands::sweep::plan::results_hash(&text)))
    }

    /// The stored result, if a readable one exists (a damaged file is simply redone).
    fn load<T: for<'de> Deserialize<'de>>(path: &Path) -> Option<T> {
        let text = std::fs::read_to_string(path).ok()?;
        serde_json::from_str(&text).ok()
    }

    fn store<T: Serialize>(path: &Path, value: &T) -> Result<()> {
        let temp = path.with_extension("json.partial");
        std::fs::write(&temp, serde_json::to_string_pretty(value)? + "\n")
            .with_context(|| format!("cannot write {}", temp.display()))?;
        std::fs::rename(&temp, path).with_context(|| format!("cannot write {}", path.display()))
    }
}

/// Part of a rolling case's cache key: cached rolls from before γ3 was fitted against the
/// contact radius (they hold the half-width fit under `gamma3`) are redone, not misread.
const ROLLING_ANALYSIS: &str = "gamma3 against the contact radius, gamma3_half_width";

/// A cached normal run: γ1, γ2 and its wall time.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct NormalRecord {
    gamma_approach: Option<f64>,
    gamma_pulloff: Option<f64>,
    wall_seconds: f64,
}

/// A cached translation run.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct CaseRecord {
    results: TranslationResults,
    wall_seconds: f64,
}

fn mean(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let v: Vec<f64> = values.flatten().filter(|x| x.is_finite()).collect();
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// ", θ = 20°" for a sliding case's substrate angle, "" without one.
fn theta_label(angle: Option<f64>) -> String {
    angle.map(|t| format!(", θ = {t}°")).unwrap_or_default()
}

/// Standard error of the mean of the finite values (sample standard deviation / √n), for
/// n ≥ 2.
fn standard_error(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let v: Vec<f64> = values.flatten().filter(|x| x.is_finite()).collect();
    let n = v.len() as f64;
    (v.len() >= 2).then(|| {
        let m = v.iter().sum::<f64>() / n;
        (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0) / n).sqrt()
    })
}

fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    let mut w = csv::Writer::from_path(path).with_context(|| format!("cannot create {}", path.display()))?;
    for row in rows {
        w.serialize(row)?;
    }
    w.flush()?;
    Ok(())
}

/// Runs a study.
pub fn run(args: &StudyArgs) -> Result<()> {
    let start = Instant::now();
    let text = std::fs::read_to_string(&args.study)
        .with_context(|| format!("cannot read study file {}", args.study.display()))?;
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
    let study_dir = args.study.parent().unwrap_or(Path::new("."));
    let base_path = study_dir.join(&study.base);
    let base_text =
        std::fs::read_to_string(&base_path).with_context(|| format!("base = {}: cannot read", base_path.display()))?;
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
    let wavelength = base
        .file
        .indenter
        .wavelength
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
    // override, so its cache entries are those of a study without `substrate_angles`.
    let base_angle = (study.kind == StudyKind::Sliding).then(|| {
        base.file
            .protocol
            .substrate_angle
            .unwrap_or(scenario::DEFAULT_SUBSTRATE_ANGLE)
    });
    let angles: Vec<Option<f64>> = match base_angle {
        Some(_) if !study.substrate_angles.is_empty() => study.substrate_angles.iter().map(|&a| Some(a)).collect(),
        other => vec![other],
    };
    let cache = RunCache::new(&out)?;
    // Validate every case before running any.
    let mut cases = Vec::new();
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
                let path = cache.path(&name, &table, &key);
                cases.push((i, d, angle, scenario, path));
            }
        }
    }
    let normals: Vec<(usize, ValidScenario, PathBuf)> = if study.kind == StudyKind::Rolling {
        let normal = normal_table(&table, &study.normal);
        amplitudes
            .iter()
            .enumerate()
            .map(|(i, &h)| {
                let changes = [format!("indenter.amplitude={h:e}")];
                let path = cache.path(&format!("normal-{i}"), &normal, &changes);
                Ok((i, build(&normal, &base_dir, &changes)?, path))
            })
            .collect::<Result<_>>()
            .context("the normal (indent_pulloff) run of the study")?
    } else {
        Vec::new()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.jobs)
        .build()
        .context("cannot set up the thread pool")?;
    let total = cases.len() + normals.len();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let report = |what: String| {
        let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if !args.quiet {
            eprintln!("[{k}/{total}] {what} ({:.0} s)", start.elapsed().as_secs_f64());
        }
    };
    let (normal_results, case_results) = pool.install(|| {
        rayon::join(
            || {
                normals
                    .par_iter()
                    .map(|(i, s, path)| {
                        if let Some(record) = RunCache::load::<NormalRecord>(path) {
                            report(format!("normal run α = {} (finished earlier)", study.alphas[*i]));
                            return Ok(((record.gamma_approach, record.gamma_pulloff), record.wall_seconds));
                        }
                        let t = Instant::now();
                        let (g1, g2) = normal_gammas(s)?;
                        let record = NormalRecord {
                            gamma_approach: g1,
                            gamma_pulloff: g2,
                            wall_seconds: t.elapsed().as_secs_f64(),
                        };
                        RunCache::store(path, &record)?;
                        report(format!("normal run α = {}", study.alphas[*i]));
                        Ok(((g1, g2), record.wall_seconds))
                    })
                    .collect::<Vec<Result<_>>>()
            },
            || {
                cases
                    .par_iter()
                    .map(|(i, d, angle, s, path)| {
                        let what = format!(
                            "{} α = {}, d = {d}·|d_JKR|{}",
                            wanted.name(),
                            study.alphas[*i],
                            theta_label(angle.filter(|_| angles.len() > 1))
                        );
                        if let Some(record) = RunCache::load::<CaseRecord>(path) {
                            report(format!("{what} (finished earlier)"));
                            return Ok((record.results, record.wall_seconds));
                        }
                        let t = Instant::now();
                        let results = translation_results(s)?;
                        let record = CaseRecord {
                            results,
                            wall_seconds: t.elapsed().as_secs_f64(),
                        };
                        RunCache::store(path, &record)?;
                        report(what);
                        Ok((record.results, record.wall_seconds))
                    })
                    .collect::<Vec<Result<_>>>()
            },
        )
    });
    let mut gammas: Vec<(Option<f64>, Option<f64>, Option<f64>)> = vec![(None, None, None); amplitudes.len()];
    for ((i, _, _), result) in normals.iter().zip(normal_results) {
        let ((g1, g2), seconds) = result.with_context(|| format!("normal run α = {}", study.alphas[*i]))?;
        gammas[*i] = (g1, g2, Some(seconds));
    }
    let f_jkr = jkr.critical_force().abs();
    let a_jkr = jkr.critical_radius();
    let mut rows = Vec::new();
    let mut per_case: Vec<(usize, TranslationResults)> = Vec::new();
    for ((i, d, angle, _, _), result) in cases.iter().zip(case_results) {
        let (r, seconds) =
            result.with_context(|| format!("case α = {}, d = {d}·|d_JKR|{}", study.alphas[*i], theta_label(*angle)))?;
        let (g1, g2, _) = gammas[*i];
        let prediction = match (g1, g2) {
            (Some(g1), Some(g2)) => Some(eq12_rolling_resistance(r.contact_half_width, g1, g2)),
            _ => None,
        };
        let ratio = |f: Option<f64>| match (f, prediction) {
            (Some(f), Some(p)) if p != 0.0 => Some(f / p),
            _ => None,
        };
        rows.push(Row {
            alpha: study.alphas[*i],
            amplitude: amplitudes[*i],
            depth_norm: *d,
            substrate_angle: *angle,
            gamma_approach_norm: g1.map(|g| g / gamma0),
            gamma_pulloff_norm: g2.map(|g| g / gamma0),
            mean_tangential_force_norm: r.mean_tangential_force.map(|f| f / f_jkr),
            mean_tangential_force_work_norm: Some(r.mean_tangential_force_work / f_jkr),
            tangential_force_fluctuation_norm: Some(r.tangential_force_fluctuation / f_jkr),
            eq12_prediction_norm: prediction.map(|p| p / f_jkr),
            eq12_ratio: ratio(r.mean_tangential_force),
            eq12_ratio_work: ratio(Some(r.mean_tangential_force_work)),
            mean_normal_force_norm: Some(r.mean_normal_force / f_jkr),
            contact_half_width_norm: Some(r.contact_half_width / a_jkr),
            contact_radius_norm: Some(r.contact_radius / a_jkr),
            compactness: r.compactness,
            boundary_force_per_width_norm: r
                .mean_tangential_force
                .filter(|_| r.contact_half_width > 0.0)
                .map(|f| f / (2.0 * r.contact_half_width * gamma0)),
            gamma3_norm: r.gamma3.map(|g| g / gamma0),
            gamma3_half_width_norm: r.gamma3_half_width.map(|g| g / gamma0),
            energy_balance_ratio: r.energy_balance_ratio,
            jumps: r.jumps,
            border_contact: r.border_contact,
            wall_seconds: seconds,
        });
        per_case.push((*i, r));
    }
    let mut alpha_rows = Vec::new();
    for (i, &alpha) in study.alphas.iter().enumerate() {
        let mine: Vec<&Row> = rows
            .iter()
            .filter(|r| r.alpha == alpha && r.amplitude == amplitudes[i])
            .collect();
        let fit_gamma3 = |radius_of: fn(&TranslationResults) -> f64| {
            let points: Vec<(f64, f64)> = per_case
                .iter()
                .filter(|(j, _)| *j == i)
                .map(|(_, r)| (radius_of(r), r.mean_normal_force))
                .collect();
            fit_jkr_work_of_adhesion(&points, jkr.radius, jkr.contact_modulus).map(|f| f.work_of_adhesion / gamma0)
        };
        let rolling = study.kind == StudyKind::Rolling;
        let gamma3 = fit_gamma3(|r| r.contact_radius).filter(|_| rolling);
        let gamma3_half_width = fit_gamma3(|r| r.contact_half_width).filter(|_| rolling);
        let (g1, g2, normal_seconds) = gammas[i];
        alpha_rows.push(AlphaRow {
            alpha,
            amplitude: amplitudes[i],
            gamma_approach_norm: g1.map(|g| g / gamma0),
            gamma_pulloff_norm: g2.map(|g| g / gamma0),
            normal_wall_seconds: normal_seconds,
            gamma3_norm: gamma3,
            gamma3_half_width_norm: gamma3_half_width,
            mean_eq12_ratio: mean(mine.iter().map(|r| r.eq12_ratio)),
            mean_eq12_ratio_work: mean(mine.iter().map(|r| r.eq12_ratio_work)),
            mean_tangential_force_norm: mean(mine.iter().map(|r| r.mean_tangential_force_norm)),
            mean_tangential_force_work_norm: mean(mine.iter().map(|r| r.mean_tangential_force_work_norm)),
            boundary_force_per_width_norm: mean(mine.iter().map(|r| r.boundary_force_per_width_norm)),
            boundary_force_per_width_sem: standard_error(mine.iter().map(|r| r.boundary_force_per_width_norm)),
            mean_tangential_force_sem: standard_error(mine.iter().map(|r| r.mean_tangential_force_norm)),
            compactness: mean(mine.iter().map(|r| Some(r.compactness))).unwrap_or(f64::NAN),
        });
    }
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
        "normal_runs": normals.len(),
        "wall_seconds": start.elapsed().as_secs_f64(),
        "jobs": args.jobs,
        "alphas": alpha_rows,
    });
    std::fs::write(out.join("study.json"), serde_json::to_string_pretty(&json)? + "\n")?;
    if !args.quiet {
        println!(
            "adhesim study {}: {} cases + {} normal runs in {:.0} s",
            wanted.name(),
            rows.len(),
            normals.len(),
            start.elapsed().as_secs_f64()
        );
        for a in &alpha_rows {
            match study.kind {
                StudyKind::Rolling => println!(
                    "  α = {:.3}: γ1/γ0 = {}, γ2/γ0 = {}, F_T/2a(γ2−γ1) = {} (per step), {} (work), γ3/γ0 = {}",
                    a.alpha,
                    show(a.gamma_approach_norm),
                    show(a.gamma_pulloff_norm),
                    show(a.mean_eq12_ratio),
                    show(a.mean_eq12_ratio_work),
                    show(a.gamma3_norm)
                ),
                StudyKind::Sliding => println!(
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
        println!(
            "outputs in {}/: table.csv, alphas.csv, study.json, {}",
            out.display(),
            plots.join(", ")
        );
    }
    Ok(())
}

fn show(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| format!("{v:.3}"))
}

fn by_alpha(alphas: &[AlphaRow], f: impl Fn(&AlphaRow) -> Option<f64>) -> Vec<(f64, f64)> {
    alphas.iter().filter_map(|a| f(a).map(|y| (a.alpha, y))).collect()
}

fn rolling_plots(dir: &Path, rows: &[Row], alphas: &[AlphaRow]) -> Result<Vec<String>> {
    let mut files = Vec::new();
    for (name, work) in [("fig7", false), ("fig7_work", true)] {
        let mut series = Vec::new();
        let mut top: f64 = 0.0;
        for (k, a) in alphas.iter().enumerate() {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.alpha == a.alpha)
                .filter_map(|r| {
                    let y = if work {
                        r.mean_tangential_force_work_norm
                    } else {
                        r.mean_tangential_force_norm
                    };
                    Some((r.eq12_prediction_norm?, y?))
                })
                .collect();
            top = points.iter().fold(top, |t, p| t.max(p.0).max(p.1));
            series.push(Series::new(
                format!("α = {:.2}", a.alpha),
                PALETTE[k % PALETTE.len()],
                Style::Points,
                points,
            ));
        }
        series.push(Series::new(
            "slope 1 (Eq. 12)",
            BLACKISH,
            Style::Dashed,
            vec![(0.0, 0.0), (top, top)],
        ));
        let which = if work { "work-based mean" } else { "per-step mean" };
        files.extend(write_panels(
            dir,
            name,
            &[Chart {
                title: format!("Rolling friction vs Eq. 12 ({which})"),
                x_label: "2a(γ2 − γ1) / |F_JKR|".into(),
                y_label: "F_T / |F_JKR|".into(),
                series,
                include_zero: true,
            }],
        )?);
    }
    let x: Vec<f64> = alphas.iter().map(|a| a.alpha).collect();
    let (lo, hi) = (
        x.iter().copied().fold(f64::INFINITY, f64::min),
        x.iter().copied().fold(0.0, f64::max),
    );
    files.extend(write_panels(
        dir,
        "fig8",
        &[Chart {
            title: "Rolling contact: effective work of adhesion γ3".into(),
            x_label: "Johnson parameter α".into(),
            y_label: "γ / γ0".into(),
            series: vec![
                Series::new(
                    "γ3 (rolling, F_N vs contact radius)",
                    PALETTE[0],
                    Style::LinePoints,
                    by_alpha(alphas, |a| a.gamma3_norm),
                ),
                Series::new(
                    "γ3 (F_N vs half-width)",
                    PALETTE[3],
                    Style::Dashed,
                    by_alpha(alphas, |a| a.gamma3_half_width_norm),
                ),
                Series::new(
                    "γ1 (approach)",
                    PALETTE[2],
                    Style::LinePoints,
                    by_alpha(alphas, |a| a.gamma_approach_norm),
                ),
                Series::new(
                    "γ2 (pull-off)",
                    PALETTE[1],
                    Style::LinePoints,
                    by_alpha(alphas, |a| a.gamma_pulloff_norm),
                ),
                Series::new("1.15 (paper)", BLACKISH, Style::Dashed, vec![(lo, 1.15), (hi, 1.15)]),
            ],
            include_zero: true,
        }],
    )?);
    Ok(files)
}

/// Per-step mean ± one standard error over the cases (substrate angles, depths) where a
/// study has more than one case per α.
fn error_band(alphas: &[AlphaRow]) -> Vec<Series> {
    if alphas.iter().all(|a| a.mean_tangential_force_sem.is_none()) {
        return Vec::new();
    }
    [1.0, -1.0]
        .iter()
        .map(|&sign| {
            Series::new(
                if sign > 0.0 { "± standard error" } else { "" },
                PALETTE[0],
                Style::Dashed,
                by_alpha(alphas, |a| {
                    Some(a.mean_tangential_force_norm? + sign * a.mean_tangential_force_sem?)
                }),
            )
        })
        .collect()
}

const BLACKISH: plotters::style::RGBColor = plotters::style::RGBColor(60, 60, 60);

fn sliding_plots(dir: &Path, alphas: &[AlphaRow]) -> Result<Vec<String>> {
    let x: Vec<f64> = alphas.iter().map(|a| a.alpha).collect();
    let (lo, hi) = (
        x.iter().copied().fold(f64::INFINITY, f64::min),
        x.iter().copied().fold(0.0, f64::max),
    );
    // Two panels: the per-step mean on its own scale (with the standard error over the
    // cases where there are several), then both means, whose scales differ by 10–50×.
    let per_step = || {
        Series::new(
            "per-step mean",
            PALETTE[0],
            Style::LinePoints,
            by_alpha(alphas, |a| a.mean_tangential_force_norm),
        )
    };
    let mut files = write_panels(
        dir,
        "fig10a",
        &[
            Chart {
                title: "Sliding: boundary contribution to friction (per-step mean)".into(),
                x_label: "Johnson parameter α".into(),
                y_label: "F_B / |F_JKR|".into(),
                series: std::iter::once(per_step()).chain(error_band(alphas)).collect(),
                include_zero: true,
            },
            Chart {
                title: "Per-step and work-based means".into(),
                x_label: "Johnson parameter α".into(),
                y_label: "F_B / |F_JKR|".into(),
                series: vec![
                    per_step(),
                    Series::new(
                        "work-based mean",
                        PALETTE[4],
                        Style::LinePoints,
                        by_alpha(alphas, |a| a.mean_tangential_force_work_norm),
                    ),
                ],
                include_zero: true,
            },
        ],
    )?;
    files.extend(write_panels(
        dir,
        "fig10b",
        &[Chart {
            title: "Sliding: compactness of the contact".into(),
            x_label: "Johnson parameter α".into(),
            y_label: "A_real / (π a²)".into(),
            series: vec![
                Series::new(
                    "A_real/(πa²)",
                    PALETTE[0],
                    Style::LinePoints,
                    by_alpha(alphas, |a| Some(a.compactness)),
                ),
                Series::new("1", BLACKISH, Style::Dashed, vec![(lo, 1.0), (hi, 1.0)]),
            ],
            include_zero: true,
        }],
    )?);
    Ok(files)
}
