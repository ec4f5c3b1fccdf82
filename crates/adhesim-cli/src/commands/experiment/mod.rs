//! `adhesim experiment`: analysis of filmed contact experiments, and `adhesim experiment synth`
//! to generate a synthetic one. Numerics live in `adhesim_experiment`; this module reads
//! frames and logs, writes `frames.csv`, `changes/`, `plots/` and `summary.json`.

mod film;
mod inputs;
mod plots;
mod spec;
mod synth;

use adhesim_experiment::fit::{fit_jkr_work_of_adhesion, friction_law_fit, pinned_phase, power_law_fit};
use adhesim_experiment::{
    change_map, classify_phases, detect_jumps, measure, AreaMeasurement, BackgroundModel, Change, GrayImage,
    IndenterTrack, Phase, SegmentationParams, Segmenter,
};
use anyhow::{bail, Context, Result};
pub use film::{run_film, FilmArgs};
use indicatif::ProgressBar;
pub use inputs::read_frame;
use inputs::{list_frames, name_of, read_table, ForceLog, FrameSize};
use rayon::prelude::*;
use serde_json::json;
use spec::{BackgroundChoice, Reference, Settings};
use std::path::{Path, PathBuf};
use std::time::Instant;
pub use synth::{run_synth, SynthArgs};

/// Arguments of `adhesim experiment`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct ExperimentArgs {
    #[command(subcommand)]
    pub command: Option<ExperimentCommand>,
    /// Experiment spec (TOML), see docs/interface-experiment.md.
    pub spec: Option<PathBuf>,
    /// Output folder (default: out/<spec file stem>/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Subcommands of `adhesim experiment`.
#[derive(Debug, clap::Subcommand)]
pub enum ExperimentCommand {
    /// Generate a synthetic experiment (frames, force log, spec) with known contact.
    Synth(SynthArgs),
    /// Film a simulated run as the camera films an experiment (frames, force log, truth, spec).
    Film(FilmArgs),
}

/// Entry point of the `experiment` subcommand.
pub fn main(args: ExperimentArgs) -> Result<()> {
    match (args.command, args.spec) {
        (Some(ExperimentCommand::Synth(synth)), _) => run_synth(&synth),
        (Some(ExperimentCommand::Film(film)), _) => run_film(&film),
        (None, Some(spec)) => {
            check_not_a_misspelt_subcommand(&spec)?;
            run_experiment(&spec, args.out.as_deref(), args.quiet)
        }
        (None, None) => {
            bail!("give a spec file (adhesim experiment SPEC.toml) or a subcommand (adhesim experiment synth)")
        }
    }
}

/// `adhesim experiment snyth` is read as a spec file: where no such file exists and the
/// name is close to a subcommand's, the error says so and suggests the subcommand.
fn check_not_a_misspelt_subcommand(spec: &Path) -> Result<()> {
    use clap::Subcommand;
    let (Some(given), false) = (spec.to_str(), spec.exists()) else {
        return Ok(());
    };
    let command = ExperimentCommand::augment_subcommands(clap::Command::new("experiment"));
    match super::similar_name(given, command.get_subcommands().map(|c| c.get_name())) {
        Some(name) => {
            bail!("experiment spec {given}: no such file; did you mean `{name}`? (adhesim experiment {name} --help)")
        }
        None => Ok(()),
    }
}

fn progress(len: usize, quiet: bool, what: &str) -> ProgressBar {
    let bar = crate::progress::bar(len as u64, crate::progress::FRAMES, crate::progress::drawn(quiet));
    bar.set_message(what.to_string());
    bar
}

// ---------------------------------------------------------------- analysis

/// Everything known about one readable frame.
struct FrameRow {
    frame: usize,
    time: f64,
    m: AreaMeasurement,
    force_normal: Option<f64>,
    force_tangential: Option<f64>,
    stage_x: Option<f64>,
    stage_z: Option<f64>,
    jump: bool,
    phase: Phase,
}

/// Bytes one frame in analysis holds per pixel, an upper estimate: the decoded image (u16
/// and a luma copy), the grey levels, the illumination-corrected and smoothed f32 copies,
/// the masks and the change map.
const FRAME_BYTES_PER_PIXEL: u128 = 32;

/// Refuses frames whose analysis, one frame per worker thread at a time, needs more memory
/// than the limits allow (`resources::memory_limit`).
fn check_frame_memory(size: &FrameSize) -> Result<()> {
    let Some(limit) = crate::resources::memory_limit(false)? else {
        return Ok(());
    };
    let threads = rayon::current_num_threads() as u128;
    let bytes = size.width as u128 * size.height as u128 * FRAME_BYTES_PER_PIXEL * threads;
    let what = format!(
        "frames.path: frames of {}×{} pixels ({} analysed at a time)",
        size.width, size.height, threads
    );
    crate::resources::check_allocation(&what, bytes, &limit)
}

fn ratio(num: Option<f64>, den: f64) -> Option<f64> {
    let v = num? / den;
    (den > 0.0 && v.is_finite()).then_some(v)
}

/// The segmenter, calibrated on up to 5 evenly spaced readable frames; the background frame,
/// the calibration frames and the region of interest are checked against `size`.
fn build_segmenter(settings: &Settings, files: &[PathBuf], size: &FrameSize) -> Result<Segmenter> {
    let background = match &settings.background {
        BackgroundChoice::None => BackgroundModel::None,
        BackgroundChoice::Fit => BackgroundModel::Fitted,
        BackgroundChoice::File(p) => {
            let frame = read_frame(p).with_context(|| format!("contact.background: cannot read {}", p.display()))?;
            size.check(&frame, &format!("contact.background {}", p.display()))?;
            BackgroundModel::Reference(frame)
        }
    };
    if let Some(roi) = settings.roi {
        roi.check_inside(size.width, size.height)?;
    }
    let params = SegmentationParams {
        polarity: settings.polarity,
        threshold: settings.threshold,
        background,
        correction: settings.correction,
        smooth_radius: settings.smooth_radius,
        open_radius: settings.open_radius,
        close_radius: settings.close_radius,
        roi: settings.roi,
    };
    let picks: Vec<usize> = if files.len() <= 5 {
        (0..files.len()).collect()
    } else {
        (0..5).map(|i| i * (files.len() - 1) / 4).collect()
    };
    let decoded: Vec<(usize, GrayImage)> = picks
        .par_iter()
        .filter_map(|&i| read_frame(&files[i]).ok().map(|s| (i, s)))
        .collect();
    let mut samples = Vec::with_capacity(decoded.len());
    for (i, sample) in decoded {
        size.check(&sample, &format!("frames.path: {}", name_of(&files[i])))?;
        samples.push(sample);
    }
    Segmenter::new(params, &samples).context("contact threshold calibration")
}

/// Runs `adhesim experiment SPEC.toml [--out DIR]`.
pub fn run_experiment(spec_path: &Path, out: Option<&Path>, quiet: bool) -> Result<()> {
    let started = Instant::now();
    let settings = spec::load(spec_path)?;
    let out_dir = match out {
        Some(d) => d.to_path_buf(),
        None => Path::new("out").join(spec_path.file_stem().unwrap_or_default()),
    };
    let files = list_frames(&settings.frames_dir)?;
    if let Reference::Frame(f) = settings.reference {
        if f >= files.len() {
            bail!(
                "changes.reference = {f} is beyond the last frame: frames are numbered 0 … {} in file-name order (the last is {})",
                files.len() - 1,
                name_of(&files[files.len() - 1])
            );
        }
    }
    let mut warnings = Vec::new();
    let (times, times_warning) = inputs::frame_times(settings.timestamps.as_deref(), settings.rate, files.len())?;
    warnings.extend(times_warning);
    let log = settings.forces.as_ref().map(ForceLog::load).transpose()?;
    if let Some(log) = &log {
        warnings.extend(log.check_overlap(&times[..files.len()])?);
        warnings.extend(log.empty_cells_warning());
    }
    let size = FrameSize::of_first(&files)
        .with_context(|| format!("no readable frames in {}", settings.frames_dir.display()))?;
    check_frame_memory(&size)?;
    let segmenter = build_segmenter(&settings, &files, &size)?;
    let track = settings
        .indenter
        .map(|(cx, cy, x0, motion)| IndenterTrack::new([cx, cy], x0, motion, settings.pixel_size))
        .transpose()?;
    if let Some(track) = &track {
        track.check_inside(size.width, size.height)?;
    }
    for w in &warnings {
        eprintln!("warning: {w}");
    }

    let decoded_at = Instant::now();
    let context = FrameContext {
        size: &size,
        segmenter: &segmenter,
        log: log.as_ref(),
        track: track.as_ref(),
        pixel_size: settings.pixel_size,
    };
    let results = context.analyse_frames(&files, &times, quiet)?;
    let analysis_seconds = decoded_at.elapsed().as_secs_f64();
    let skipped: Vec<String> = files
        .iter()
        .zip(&results)
        .filter(|(_, r)| r.is_none())
        .map(|(p, _)| name_of(p))
        .collect();
    let mut rows: Vec<FrameRow> = results.into_iter().flatten().collect();
    if rows.is_empty() {
        bail!("no readable frames in {}", settings.frames_dir.display());
    }
    if let Reference::Frame(f) = settings.reference {
        if !rows.iter().any(|r| r.frame == f) {
            bail!(
                "changes.reference = {f} names {}, which could not be read",
                name_of(&files[f])
            );
        }
    }
    mark_jumps_and_phases(&mut rows, &settings)?;

    std::fs::create_dir_all(out_dir.join("plots")).with_context(|| format!("cannot create {}", out_dir.display()))?;
    std::fs::create_dir_all(out_dir.join("changes"))?;
    write_frames_csv(&out_dir.join("frames.csv"), &rows)?;
    let changes_written = write_change_maps(&settings, &files, &rows, &segmenter, &out_dir.join("changes"))?;
    plots::write_plots(&out_dir.join("plots"), &rows)?;
    let results = fit_results(&settings, &rows)?;
    let summary = json!({
        "inputs": {
            "spec": spec_path.display().to_string(),
            "frames_path": settings.frames_dir.display().to_string(),
            "pixel_size": settings.pixel_size,
            "threshold": finite(f64::from(segmenter.threshold())),
        },
        "frames": { "listed": files.len(), "analysed": rows.len(), "skipped": skipped, "change_maps": changes_written },
        "warnings": warnings,
        "results": results,
        "performance": {
            "wall_seconds": started.elapsed().as_secs_f64(),
            "analysis_seconds": analysis_seconds,
            "frames_per_second": finite(rows.len() as f64 / analysis_seconds.max(1e-9)),
        },
    });
    std::fs::write(out_dir.join("summary.json"), serde_json::to_string_pretty(&summary)?)?;
    if !quiet {
        eprintln!(
            "analysed {} of {} frames into {}",
            rows.len(),
            files.len(),
            out_dir.display()
        );
    }
    Ok(())
}

/// Sequence-level analysis: the jumps and stick/slip phases over the readable frames.
fn mark_jumps_and_phases(rows: &mut [FrameRow], settings: &Settings) -> Result<()> {
    let areas: Vec<f64> = rows.iter().map(|r| r.m.area).collect();
    let jumps = detect_jumps(&areas, settings.phases.jump_threshold)?;
    let xs: Vec<f64> = rows.iter().map(|r| r.stage_x.unwrap_or(f64::NAN)).collect();
    let fxs: Vec<f64> = rows.iter().map(|r| r.force_tangential.unwrap_or(f64::NAN)).collect();
    let has_motion = xs.iter().any(|v| v.is_finite()) && fxs.iter().any(|v| v.is_finite());
    let phases = classify_phases(&areas, has_motion.then_some((&xs[..], &fxs[..])), &settings.phases)?;
    for ((r, j), p) in rows.iter_mut().zip(jumps).zip(phases) {
        r.jump = j;
        r.phase = p;
    }
    Ok(())
}

/// What every frame's analysis shares.
struct FrameContext<'a> {
    size: &'a FrameSize,
    segmenter: &'a Segmenter,
    log: Option<&'a ForceLog>,
    track: Option<&'a IndenterTrack>,
    pixel_size: f64,
}

impl FrameContext<'_> {
    /// Analyses every frame in parallel: `None` for an unreadable frame (named on stderr and
    /// skipped); an error (a frame of another size) stops the run.
    fn analyse_frames(&self, files: &[PathBuf], times: &[f64], quiet: bool) -> Result<Vec<Option<FrameRow>>> {
        let bar = progress(files.len(), quiet, "frames");
        // Outer error: a frame of another size stops the run; inner: an unreadable frame is skipped.
        let results: Vec<Result<Option<FrameRow>>> = files
            .par_iter()
            .enumerate()
            .map(|(i, path)| {
                let row = self.analyse_frame(i, path, times[i]);
                bar.inc(1);
                Ok(match row? {
                    Ok(r) => Some(r),
                    Err(e) => {
                        bar.suspend(|| {
                            eprintln!(
                                "skipping unreadable frame {}: {}",
                                name_of(path),
                                adhesim_scenario::error_text::error_line(e.chain())
                            )
                        });
                        None
                    }
                })
            })
            .collect();
        bar.finish_and_clear();
        results.into_iter().collect()
    }

    /// One frame: `Err` for a frame of another size (the run stops), `Ok(Err)` for a frame
    /// that cannot be decoded or segmented (it is skipped and reported).
    fn analyse_frame(&self, index: usize, path: &Path, time: f64) -> Result<Result<FrameRow>> {
        let image = match read_frame(path) {
            Ok(image) => image,
            Err(e) => return Ok(Err(e)),
        };
        self.size.check(&image, &format!("frames.path: {}", name_of(path)))?;
        Ok(self.measure_frame(index, &image, time))
    }

    fn measure_frame(&self, index: usize, image: &GrayImage, time: f64) -> Result<FrameRow> {
        let mask = self.segmenter.segment(image)?;
        let channel = |c: usize| self.log.and_then(|l| l.at(c, time));
        let stage_x = channel(2);
        let split = self
            .track
            .map(|t| (t.centre_at(stage_x.unwrap_or(t.stage_x0)), t.motion));
        let m = measure(&mask, self.pixel_size, split)?;
        Ok(FrameRow {
            frame: index,
            time,
            m,
            force_normal: channel(0),
            force_tangential: channel(1),
            stage_x,
            stage_z: channel(3),
            jump: false,
            phase: Phase::Undetermined,
        })
    }
}

/// JSON number, or null for anything non-finite (never NaN in outputs).
fn finite(v: f64) -> serde_json::Value {
    if v.is_finite() {
        json!(v)
    } else {
        serde_json::Value::Null
    }
}

fn cell(v: Option<f64>) -> String {
    v.filter(|v| v.is_finite()).map_or_else(String::new, |v| format!("{v}"))
}

fn write_frames_csv(path: &Path, rows: &[FrameRow]) -> Result<()> {
    let mut w = csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record([
        "frame",
        "time",
        "area",
        "area_front",
        "area_rear",
        "force_normal",
        "force_tangential",
        "pressure",
        "tangential_stress",
        "stage_x",
        "stage_z",
        "jump",
        "phase",
        "pixels",
        "centroid_x_px",
        "centroid_y_px",
        "width",
        "length",
    ])?;
    for r in rows {
        let c = r.m.centroid_px;
        w.write_record([
            r.frame.to_string(),
            cell(Some(r.time)),
            cell(Some(r.m.area)),
            cell(Some(r.m.area_front)),
            cell(Some(r.m.area_rear)),
            cell(r.force_normal),
            cell(r.force_tangential),
            cell(ratio(r.force_normal, r.m.area)),
            cell(ratio(r.force_tangential, r.m.area)),
            cell(r.stage_x),
            cell(r.stage_z),
            u8::from(r.jump).to_string(),
            r.phase.name().to_string(),
            r.m.pixels.to_string(),
            cell(c.map(|c| c[0])),
            cell(c.map(|c| c[1])),
            cell(Some(r.m.width)),
            cell(Some(r.m.length)),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// Change-map overlays on the raw frame: new contact red, vanished contact blue.
fn write_change_maps(
    settings: &Settings,
    files: &[PathBuf],
    rows: &[FrameRow],
    segmenter: &Segmenter,
    dir: &Path,
) -> Result<usize> {
    // Pairs (reference row, current row) by position in `rows`.
    let mut picks: Vec<(usize, usize)> = Vec::new();
    let reference_of = |k: usize| -> Option<usize> {
        match settings.reference {
            Reference::First => (k > 0).then_some(0),
            Reference::Previous => k.checked_sub(1),
            Reference::Frame(f) => rows.iter().position(|r| r.frame == f).filter(|&p| p != k),
        }
    };
    for (k, r) in rows.iter().enumerate() {
        let scheduled = settings.changes_every > 0 && r.frame % settings.changes_every == 0;
        if scheduled || (settings.changes_at_jumps && r.jump) {
            if let Some(reference) = reference_of(k) {
                picks.push((reference, k));
            }
        }
    }
    if picks.len() > settings.changes_max {
        // Keep an evenly spread subset.
        let n = picks.len();
        picks = (0..settings.changes_max)
            .map(|i| picks[i * n / settings.changes_max])
            .collect();
    }
    let written: Vec<Result<()>> = picks
        .par_iter()
        .map(|&(a, b)| {
            let (ra, rb) = (&rows[a], &rows[b]);
            let reference_mask = segmenter.segment(&read_frame(&files[ra.frame])?)?;
            let raw = read_frame(&files[rb.frame])?;
            let current_mask = segmenter.segment(&raw)?;
            let map = change_map(&reference_mask, &current_mask)?;
            let (x0, y0, x1, y1) = crop_box(&reference_mask, &current_mask, CHANGE_MAP_MARGIN_PX);
            let width = raw.width();
            let mut rgb = image::RgbImage::new((x1 - x0) as u32, (y1 - y0) as u32);
            for (y, row) in (y0..y1).zip(rgb.rows_mut()) {
                for (x, px) in (x0..x1).zip(row) {
                    let i = y * width + x;
                    let g = (raw.pixels()[i].clamp(0.0, 1.0) * 255.0) as u8;
                    *px = match map.changes()[i] {
                        Change::New => image::Rgb([255, 0, 0]),
                        Change::Vanished => image::Rgb([0, 0, 255]),
                        Change::Unchanged => image::Rgb([g, g, g]),
                    };
                }
            }
            let name = format!("change_{:05}_vs_{:05}.png", rb.frame, ra.frame);
            // The key: new and vanished contact, and a scale bar in the length unit of
            // frames.pixel_size (one image pixel per camera pixel).
            let legend = [([255, 0, 0], "new contact"), ([0, 0, 255], "vanished contact")];
            let keyed = adhesim_figures::map_key::with_key(
                &rgb,
                1.0 / settings.pixel_size,
                adhesim_figures::map_key::Legend::Categories(&legend),
            )?;
            adhesim_figures::figure::files::save_image(&keyed, &dir.join(&name))?;
            Ok(())
        })
        .collect();
    let mut count = 0;
    for r in written {
        match r {
            Ok(()) => count += 1,
            Err(e) => eprintln!("change map skipped: {e:#}"),
        }
    }
    Ok(count)
}

/// Change maps show the contact's bounding box (both masks) plus this margin, like the
/// paper's Figs. 16 and 24; the whole frame when there is no contact.
const CHANGE_MAP_MARGIN_PX: usize = 20;

/// Bounding box [x0, x1) × [y0, y1) of the union of two masks, widened by `margin`.
fn crop_box(
    a: &adhesim_experiment::ContactMask,
    b: &adhesim_experiment::ContactMask,
    margin: usize,
) -> (usize, usize, usize, usize) {
    let (w, h) = (a.width(), a.height());
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for y in 0..h {
        for x in 0..w {
            if a.get(x, y) || b.get(x, y) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1));
            }
        }
    }
    if x0 == usize::MAX {
        return (0, 0, w, h);
    }
    (
        x0.saturating_sub(margin),
        y0.saturating_sub(margin),
        (x1 + margin).min(w),
        (y1 + margin).min(h),
    )
}

fn fit_results(settings: &Settings, rows: &[FrameRow]) -> Result<serde_json::Value> {
    let areas: Vec<f64> = rows.iter().map(|r| r.m.area).collect();
    let max_area = areas.iter().copied().fold(0.0, f64::max);
    let jumps = rows.iter().filter(|r| r.jump).count();
    let stick = rows.iter().filter(|r| r.phase == Phase::Stick).count();
    // Friction law (Eq. 18) on frames with a tangential force and contact, in the window.
    let in_window = |t: f64| settings.fits.friction_window.is_none_or(|[t0, t1]| t >= t0 && t <= t1);
    let (fa, ft): (Vec<f64>, Vec<f64>) = rows
        .iter()
        .filter(|r| in_window(r.time))
        .filter_map(|r| ratio(r.force_tangential, r.m.area).map(|tau| (r.m.area, tau)))
        .unzip();
    let mean_stress = (!ft.is_empty()).then(|| ft.iter().sum::<f64>() / ft.len() as f64);
    let friction = friction_law_fit(&fa, &ft)
        .ok()
        .map(|f| json!({"tau0": finite(f.tau0), "q": finite(f.q), "r2": finite(f.r2), "points": f.points}));
    // Normal curve: JKR fits on approach and pull-off, pinned phase after reversal.
    let depth: Vec<f64> = rows.iter().map(|r| r.stage_z.unwrap_or(f64::NAN)).collect();
    let radius: Vec<f64> = areas.iter().map(|a| (a / std::f64::consts::PI).sqrt()).collect();
    let force: Vec<f64> = rows.iter().map(|r| r.force_normal.unwrap_or(f64::NAN)).collect();
    let pinned = pinned_phase(&depth, &radius, settings.fits.pinned_tolerance.unwrap_or(0.01))?
        .filter(|p| p.last > p.reversal && depth.iter().any(|d| d.is_finite() && *d != depth[p.reversal]));
    let (mut gamma_approach, mut gamma_pulloff) = (None, None);
    if let (Some(e), Some(r), Some(p)) = (settings.fits.contact_modulus, settings.fits.indenter_radius, pinned) {
        // (contact radius, force) pairs of each branch; the spec has checked e, r > 0.
        let branch =
            |range: std::ops::Range<usize>| -> Vec<(f64, f64)> { range.map(|i| (radius[i], force[i])).collect() };
        gamma_approach = fit_jkr_work_of_adhesion(&branch(0..p.reversal + 1), r, e).map(|f| f.work_of_adhesion);
        gamma_pulloff = fit_jkr_work_of_adhesion(&branch(p.last + 1..force.len()), r, e).map(|f| f.work_of_adhesion);
    }
    let power_law = match &settings.fits.power_law {
        Some(pl) => {
            let cols = read_table(&pl.path, &[pl.time.as_str(), pl.force.as_str()], "fits.power_law")?.columns;
            let t: Vec<f64> = cols[0].iter().map(|v| v.unwrap_or(f64::NAN)).collect();
            let f: Vec<f64> = cols[1].iter().map(|v| v.unwrap_or(f64::NAN)).collect();
            power_law_fit(&t, &f).ok().map(|p| json!({"coefficient": finite(p.coefficient), "exponent": finite(p.exponent), "r2": finite(p.r2), "points": p.points}))
        }
        None => None,
    };
    let max_adhesive = force
        .iter()
        .filter(|f| f.is_finite() && **f < 0.0)
        .fold(None, |m: Option<f64>, f| Some(m.map_or(-f, |m| m.max(-f))));
    Ok(json!({
        "max_area": finite(max_area),
        "jumps": jumps,
        "stick_frames": stick,
        "mean_tangential_stress": mean_stress.map(finite),
        "max_adhesive_force": max_adhesive.map(finite),
        "friction_law": friction,
        "pinned_phase_depth": pinned.map(|p| finite(p.depth_span)),
        "gamma_approach": gamma_approach.map(finite),
        "gamma_pulloff": gamma_pulloff.map(finite),
        "boundary_friction": gamma_approach.zip(gamma_pulloff).map(|(g1, g2)| finite((g2 - g1) / 2.0)),
        "power_law": power_law,
    }))
}
